// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/tolerance_allowances.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "geometry/exact_normal_signs.h"
#include "geometry/undercut_depth.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/geometry/axis.h"

namespace subfab {

namespace {

void check(const ToleranceAllowanceOptions& options) {
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
    throw InvalidArgumentError("tolerance_allowances: the tolerance must be positive");
  if (!(options.depth_fraction > 0)) throw InvalidArgumentError("tolerance_allowances: depth_fraction must be positive");
}

}  // namespace

std::vector<std::array<double, 3>> undercut_depths(const Mesh& mesh, const ToleranceAllowanceOptions& options) {
  check(options);
  const BoundingBox box = bounding_box(mesh);
  const detail::UndercutDepth depth(mesh);
  const auto signs = detail::exact_normal_signs(mesh);
  const double limit = options.depth_fraction * options.tolerance;
  constexpr double none = std::numeric_limits<double>::infinity();
  std::vector<std::array<double, 3>> depths(mesh.num_faces(), {none, none, none});
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
          depths[f][static_cast<std::size_t>(k)] = depth.depth(f, d, cap, limit);
        }
      },
      256);
  return depths;
}

std::vector<std::uint8_t> allowances_at(const std::vector<std::array<double, 3>>& depths,
                                        const std::vector<std::array<std::uint8_t, 3>>& level,
                                        const std::vector<double>& fractions, double tolerance) {
  if (level.size() != depths.size()) throw InvalidArgumentError("allowances_at: one level per face expected");
  std::vector<std::uint8_t> allowed(depths.size(), 0);
  for (std::size_t f = 0; f < depths.size(); ++f)
    for (std::size_t k = 0; k < 3; ++k)
      if (level[f][k] < fractions.size() && depths[f][k] <= fractions[level[f][k]] * tolerance)
        allowed[f] = static_cast<std::uint8_t>(allowed[f] | (1u << k));
  return allowed;
}

std::vector<std::uint8_t> tolerance_allowances(const Mesh& mesh, const ToleranceAllowanceOptions& options) {
  const std::vector<std::array<double, 3>> depths = undercut_depths(mesh, options);
  const std::vector<std::uint8_t> allowed =
      allowances_at(depths, std::vector<std::array<std::uint8_t, 3>>(depths.size(), {0, 0, 0}),
                    {options.depth_fraction}, options.tolerance);
  if (options.progress)
    options.progress->info(std::to_string(count_allowed_faces(allowed)) + " of " + std::to_string(mesh.num_faces()) +
                           " faces may lean past vertical (undercut within the tolerance)");
  return allowed;
}

OverhangAllowances allowances_with_floors(const Mesh& mesh, const std::vector<std::array<double, 3>>& depths,
                                          const std::vector<std::array<std::uint8_t, 3>>& level,
                                          const std::vector<double>& fractions, double tolerance, double floor_scale) {
  if (depths.size() != mesh.num_faces())
    throw InvalidArgumentError("allowances_with_floors: one depth per face expected");
  constexpr double inf = std::numeric_limits<double>::infinity();
  OverhangAllowances a;
  a.bits = allowances_at(depths, level, fractions, tolerance);
  a.floors.assign(mesh.num_faces(), {-inf, -inf, -inf});
  if (!(floor_scale > 0)) return a;
  const auto signs = detail::exact_normal_signs(mesh);
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 n = face_unit_normal(mesh, f);
    for (std::size_t k = 0; k < 3; ++k) {
      const auto bit = static_cast<std::uint8_t>(1u << k);
      if ((a.bits[f] & bit) || level[f][k] >= fractions.size() || signs[f][k] == 0) continue;
      const double cosine = std::abs(n[static_cast<int>(k)]);
      if (!(cosine > 0)) continue;
      // d = -s e_k: v.d = -s v_k.
      const int s = signs[f][k];
      double top = -inf;
      for (int v : mesh.faces[f]) top = std::max(top, -s * mesh.vertices[static_cast<std::size_t>(v)][static_cast<int>(k)]);
      a.floors[f][k] = top - floor_scale * fractions[level[f][k]] * tolerance / cosine;
      a.bits[f] = static_cast<std::uint8_t>(a.bits[f] | bit);
    }
  }
  return a;
}

OverhangAllowances uniform_overhang_allowances(const Mesh& mesh, double max_overhang_deg) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  OverhangAllowances a;
  a.bits.assign(mesh.num_faces(), 0);
  a.floors.assign(mesh.num_faces(), {-inf, -inf, -inf});
  if (!(max_overhang_deg > 0)) return a;
  const auto exact = detail::exact_normal_signs(mesh);
  const auto facing = detail::facing_signs(mesh, overhang_sine(max_overhang_deg));
  for (std::size_t f = 0; f < mesh.num_faces(); ++f)
    for (std::size_t k = 0; k < 3; ++k)
      if (exact[f][k] != 0 && facing[f][k] == 0) a.bits[f] = static_cast<std::uint8_t>(a.bits[f] | (1u << k));
  return a;
}

std::size_t count_floored_faces(const OverhangAllowances& allowances) {
  std::size_t n = 0;
  for (std::size_t f = 0; f < allowances.bits.size(); ++f) {
    bool allowed = false, somewhere_everywhere = false;
    for (std::size_t k = 0; k < 3; ++k)
      if (allowances.bits[f] & (1u << k)) {
        allowed = true;
        if (!std::isfinite(allowances.floors[f][k])) somewhere_everywhere = true;
      }
    if (allowed && !somewhere_everywhere) ++n;
  }
  return n;
}

std::size_t count_changed_faces(const OverhangAllowances& before, const OverhangAllowances& after) {
  std::size_t n = 0;
  for (std::size_t f = 0; f < before.bits.size() && f < after.bits.size(); ++f) {
    bool changed = before.bits[f] != after.bits[f];
    for (std::size_t k = 0; k < 3 && !changed; ++k)
      changed = (after.bits[f] & (1u << k)) && before.floors[f][k] != after.floors[f][k];
    if (changed) ++n;
  }
  return n;
}

std::size_t count_allowed_faces(const std::vector<std::uint8_t>& allowed) {
  return static_cast<std::size_t>(std::count_if(allowed.begin(), allowed.end(), [](std::uint8_t a) { return a != 0; }));
}

}  // namespace subfab
