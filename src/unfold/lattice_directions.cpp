// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/lattice_directions.h"

#include <cmath>

namespace subfab {

const std::array<std::array<int, 3>, 26>& lattice_directions() {
  static const auto kDirections = [] {
    std::array<std::array<int, 3>, 26> dirs{};
    std::size_t k = 0;
    for (int x = -1; x <= 1; ++x)
      for (int y = -1; y <= 1; ++y)
        for (int z = -1; z <= 1; ++z)
          if (x != 0 || y != 0 || z != 0) dirs[k++] = {x, y, z};
    return dirs;
  }();
  return kDirections;
}

std::optional<int> lattice_direction_index(const Vec3& normal, double angle_tolerance) {
  const double len = normal.norm();
  if (!(len > 0) || !std::isfinite(len)) return std::nullopt;
  const Vec3 n = normal / len;
  // Compare the sine of the angle (|n x d|): the cosine is too flat near 0.
  const double max_sin = std::sin(angle_tolerance);
  const auto& dirs = lattice_directions();
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    const Vec3 d = Vec3(dirs[i][0], dirs[i][1], dirs[i][2]).normalized();
    if (n.dot(d) > 0 && n.cross(d).norm() <= max_sin) return static_cast<int>(i);
  }
  return std::nullopt;
}

}  // namespace subfab
