// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/geometry/rotate_into_frame.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <vector>

#include "geometry/exact_normal_signs.h"

namespace subfab {

Mesh rotate_into_frame(const Mesh& mesh, const Eigen::Matrix3d& rotation, double snap_tolerance) {
  if (rotation.isIdentity(0.0)) return mesh;
  Mesh turned = mesh;
  transform_mesh(turned, rotation, Vec3::Zero());
  return snap_coordinates(turned, snap_tolerance);
}

Mesh snap_coordinates(const Mesh& mesh, double snap_tolerance) {
  const double tolerance = snap_tolerance * bounding_box(mesh).diagonal();
  if (!(tolerance > 0) || mesh.vertices.empty()) return mesh;
  Mesh snapped = mesh;
  std::vector<std::size_t> order(snapped.vertices.size());
  for (int k = 0; k < 3; ++k) {
    std::iota(order.begin(), order.end(), 0);
    const auto coord = [&](std::size_t v) { return snapped.vertices[v][k]; };
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return coord(a) < coord(b); });
    for (std::size_t i = 0; i < order.size();) {
      std::size_t j = i + 1;
      while (j < order.size() && coord(order[j]) - coord(order[j - 1]) <= tolerance) ++j;
      if (j - i > 1) {
        const double median = coord(order[i + (j - i) / 2]);
        for (std::size_t m = i; m < j; ++m) snapped.vertices[order[m]][k] = median;
      }
      i = j;
    }
  }
  const auto before = detail::exact_normal_signs(mesh);
  const auto after = detail::exact_normal_signs(snapped);
  for (std::size_t f = 0; f < after.size(); ++f)
    if (after[f] == std::array<std::int8_t, 3>{0, 0, 0} && before[f] != after[f]) return mesh;
  return snapped;
}

}  // namespace subfab

