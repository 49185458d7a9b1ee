// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/tolerance_allowances.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/exact_normal_signs.h"
#include "geometry/undercut_depth.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {

std::vector<std::uint8_t> tolerance_allowances(const Mesh& mesh, const ToleranceAllowanceOptions& options) {
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
    throw InvalidArgumentError("tolerance_allowances: the tolerance must be positive");
  if (!(options.depth_fraction > 0)) throw InvalidArgumentError("tolerance_allowances: depth_fraction must be positive");
  const BoundingBox box = bounding_box(mesh);
  const detail::UndercutDepth depth(mesh);
  const auto signs = detail::exact_normal_signs(mesh);
  const double limit = options.depth_fraction * options.tolerance;
  std::vector<std::uint8_t> allowed(mesh.num_faces(), 0);
  parallel_for(
      0, mesh.num_faces(),
      [&](std::size_t f) {
        const Triangle& t = mesh.faces[f];
        for (int k = 0; k < 3; ++k) {
          const int s = signs[f][static_cast<std::size_t>(k)];
          if (s == 0) continue;
          // The face faces away from d = -s e_k; the fill under it runs along s e_k.
          Vec3 d = Vec3::Zero();
          d[k] = -s;
          double top = -std::numeric_limits<double>::infinity();
          for (int v : t) top = std::max(top, mesh.vertices[static_cast<std::size_t>(v)].dot(d));
          const double bottom = s > 0 ? -box.max[k] : box.min[k];  // min over the model of v.d
          const double cap = std::min(options.max_height, top - bottom);
          if (depth.depth(f, d, cap, limit) <= limit) allowed[f] |= static_cast<std::uint8_t>(1u << k);
        }
      },
      256);
  if (options.progress)
    options.progress->info(std::to_string(count_allowed_faces(allowed)) + " of " + std::to_string(mesh.num_faces()) +
                           " faces may lean past vertical (undercut within the tolerance)");
  return allowed;
}

std::size_t count_allowed_faces(const std::vector<std::uint8_t>& allowed) {
  return static_cast<std::size_t>(std::count_if(allowed.begin(), allowed.end(), [](std::uint8_t a) { return a != 0; }));
}

}  // namespace subfab
