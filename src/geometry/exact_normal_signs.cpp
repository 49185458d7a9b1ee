// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/exact_normal_signs.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "subfab/core/parallel.h"

namespace subfab::detail {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;

//! Exact sign of (b - a).u * (c - a).v - (b - a).v * (c - a).u.
std::int8_t projected_orientation(const Vec3& a, const Vec3& b, const Vec3& c, int u, int v) {
  return static_cast<std::int8_t>(
      CGAL::orientation(Point2(a[u], a[v]), Point2(b[u], b[v]), Point2(c[u], c[v])));
}
}  // namespace

std::array<std::int8_t, 3> exact_normal_signs(const Vec3& a, const Vec3& b, const Vec3& c) {
  // n_x = orient(yz), n_y = orient(zx), n_z = orient(xy): the cyclic order
  // (u, v) = (w + 1, w + 2) gives component w of the cross product.
  return {projected_orientation(a, b, c, 1, 2), projected_orientation(a, b, c, 2, 0),
          projected_orientation(a, b, c, 0, 1)};
}

std::array<std::int8_t, 3> facing_signs(const Vec3& a, const Vec3& b, const Vec3& c, double overhang_sine) {
  std::array<std::int8_t, 3> signs = exact_normal_signs(a, b, c);
  if (overhang_sine <= 0.0 || (signs[0] == 0 && signs[1] == 0 && signs[2] == 0)) return signs;
  const Vec3 n = (b - a).cross(c - a).normalized();
  for (int k = 0; k < 3; ++k)
    signs[static_cast<std::size_t>(k)] = n[k] < -overhang_sine ? -1 : (n[k] > overhang_sine ? 1 : 0);
  return signs;
}

std::vector<std::array<std::int8_t, 3>> facing_signs(const Mesh& mesh, double overhang_sine) {
  std::vector<std::array<std::int8_t, 3>> signs(mesh.num_faces());
  parallel_for(
      0, mesh.num_faces(),
      [&](std::size_t f) {
        const auto& t = mesh.faces[f];
        signs[f] = facing_signs(mesh.vertices[static_cast<std::size_t>(t[0])],
                                mesh.vertices[static_cast<std::size_t>(t[1])],
                                mesh.vertices[static_cast<std::size_t>(t[2])], overhang_sine);
      },
      1024);
  return signs;
}

std::vector<std::array<std::int8_t, 3>> exact_normal_signs(const Mesh& mesh) { return facing_signs(mesh, 0.0); }

}  // namespace subfab::detail
