// SPDX-License-Identifier: GPL-3.0-or-later
#include "decompose/classify_grid_points.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>

#include "decompose/exact_normal_signs.h"
#include "subfab/core/parallel.h"

namespace subfab::detail {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;
using Point3 = Kernel::Point_3;

//! Sign of orient2d(p, q, (qu, qv) + (e, e^2)) for an infinitesimal e > 0;
//! never 0 when p != q.
int perturbed_edge_sign(const Point2& p, const Point2& q, const Point2& query) {
  const auto o = CGAL::orientation(p, q, query);
  if (o != CGAL::COLLINEAR) return static_cast<int>(o);
  if (p.y() != q.y()) return p.y() > q.y() ? 1 : -1;  // coefficient of e: p_v - q_v
  return q.x() > p.x() ? 1 : -1;                      // coefficient of e^2: q_u - p_u
}

//! Faces whose projection along `dim` may contain each grid line (exact bounding-box filter):
//! CSR over lines, faces in increasing order per line. Faces parallel to the
//! line (exact zero normal component) are left out.
struct LineBuckets {
  std::vector<std::size_t> offsets;
  std::vector<int> faces;
};

LineBuckets bucket_faces(const Mesh& mesh, const GridGeometry& grid, int dim,
                         const std::vector<std::array<std::int8_t, 3>>& signs) {
  const int u = (dim + 1) % 3, v = (dim + 2) % 3;
  const int nu = grid.num_points[static_cast<std::size_t>(u)];
  const int nv = grid.num_points[static_cast<std::size_t>(v)];
  const std::size_t num_faces = mesh.num_faces();
  // Per face: the line index ranges (computed in parallel, used serially).
  std::vector<std::array<int, 4>> ranges(num_faces);
  parallel_for(
      0, num_faces,
      [&](std::size_t f) {
        if (signs[f][static_cast<std::size_t>(dim)] == 0) {
          ranges[f] = {0, -1, 0, -1};
          return;
        }
        const auto& t = mesh.faces[f];
        double lo_u = INFINITY, hi_u = -INFINITY, lo_v = INFINITY, hi_v = -INFINITY;
        for (int c : t) {
          const Vec3& p = mesh.vertices[static_cast<std::size_t>(c)];
          lo_u = std::min(lo_u, p[u]);
          hi_u = std::max(hi_u, p[u]);
          lo_v = std::min(lo_v, p[v]);
          hi_v = std::max(hi_v, p[v]);
        }
        ranges[f] = {grid.index_at_or_above(u, lo_u), grid.index_at_or_below(u, hi_u),
                     grid.index_at_or_above(v, lo_v), grid.index_at_or_below(v, hi_v)};
      },
      1024);
  LineBuckets buckets;
  const std::size_t num_lines = static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv);
  buckets.offsets.assign(num_lines + 1, 0);
  for (const auto& r : ranges)
    for (int b = r[2]; b <= r[3]; ++b)
      for (int a = r[0]; a <= r[1]; ++a) ++buckets.offsets[static_cast<std::size_t>(a + nu * b) + 1];
  for (std::size_t l = 0; l < num_lines; ++l) buckets.offsets[l + 1] += buckets.offsets[l];
  buckets.faces.resize(buckets.offsets[num_lines]);
  std::vector<std::size_t> fill(buckets.offsets.begin(), buckets.offsets.end() - 1);
  for (std::size_t f = 0; f < num_faces; ++f) {
    const auto& r = ranges[f];
    for (int b = r[2]; b <= r[3]; ++b)
      for (int a = r[0]; a <= r[1]; ++a)
        buckets.faces[fill[static_cast<std::size_t>(a + nu * b)]++] = static_cast<int>(f);
  }
  return buckets;
}

//! Calls fn(line, a, b, crossed_faces) for every grid line parallel to `dim`,
//! in parallel, where crossed_faces are the faces the perturbed line crosses
//! (increasing face order).
template <typename Fn>
void for_each_line(const Mesh& mesh, const GridGeometry& grid, int dim,
                   const std::vector<std::array<std::int8_t, 3>>& signs, const Fn& fn) {
  const int u = (dim + 1) % 3, v = (dim + 2) % 3;
  const int nu = grid.num_points[static_cast<std::size_t>(u)];
  const int nv = grid.num_points[static_cast<std::size_t>(v)];
  const LineBuckets buckets = bucket_faces(mesh, grid, dim, signs);
  const std::size_t num_lines = static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv);
  parallel_for(
      0, num_lines,
      [&](std::size_t line) {
        const int a = static_cast<int>(line % static_cast<std::size_t>(nu));
        const int b = static_cast<int>(line / static_cast<std::size_t>(nu));
        const Point2 query(grid.coordinate(u, a), grid.coordinate(v, b));
        std::vector<int> crossed;
        for (std::size_t e = buckets.offsets[line]; e < buckets.offsets[line + 1]; ++e) {
          const int f = buckets.faces[e];
          const auto& t = mesh.faces[static_cast<std::size_t>(f)];
          std::array<Point2, 3> q;
          for (int c = 0; c < 3; ++c) {
            const Vec3& p = mesh.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>(c)])];
            q[static_cast<std::size_t>(c)] = Point2(p[u], p[v]);
          }
          const int s0 = perturbed_edge_sign(q[0], q[1], query);
          if (perturbed_edge_sign(q[1], q[2], query) != s0) continue;
          if (perturbed_edge_sign(q[2], q[0], query) != s0) continue;
          crossed.push_back(f);
        }
        fn(line, a, b, crossed);
      },
      16);
}

//! Coordinate along dim where the line (U, V) meets the plane of face f (rounded).
double crossing_position(const Mesh& mesh, std::size_t f, int dim, double coord_u, double coord_v) {
  const int u = (dim + 1) % 3, v = (dim + 2) % 3;
  const auto& t = mesh.faces[f];
  const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
  const Vec3 n = (mesh.vertices[static_cast<std::size_t>(t[1])] - a).cross(mesh.vertices[static_cast<std::size_t>(t[2])] - a);
  return a[dim] - (n[u] * (coord_u - a[u]) + n[v] * (coord_v - a[v])) / n[dim];
}

}  // namespace

LineCrossings compute_line_crossings(const Mesh& mesh, const GridGeometry& grid, int dim) {
  const int u = (dim + 1) % 3, v = (dim + 2) % 3;
  LineCrossings result;
  result.dim = dim;
  result.num_lines = {grid.num_points[static_cast<std::size_t>(u)], grid.num_points[static_cast<std::size_t>(v)]};
  const std::size_t num_lines =
      static_cast<std::size_t>(result.num_lines[0]) * static_cast<std::size_t>(result.num_lines[1]);
  const auto signs = exact_normal_signs(mesh);
  std::vector<std::vector<double>> per_line(num_lines);
  for_each_line(mesh, grid, dim, signs, [&](std::size_t line, int a, int b, const std::vector<int>& crossed) {
    auto& out = per_line[line];
    out.reserve(crossed.size());
    for (int f : crossed)
      out.push_back(crossing_position(mesh, static_cast<std::size_t>(f), dim, grid.coordinate(u, a), grid.coordinate(v, b)));
    std::sort(out.begin(), out.end());
  });
  result.offsets.assign(num_lines + 1, 0);
  for (std::size_t l = 0; l < num_lines; ++l) result.offsets[l + 1] = result.offsets[l] + per_line[l].size();
  result.positions.reserve(result.offsets[num_lines]);
  for (const auto& line : per_line) result.positions.insert(result.positions.end(), line.begin(), line.end());
  return result;
}

std::vector<std::uint8_t> classify_grid_points(const Mesh& mesh, const GridGeometry& grid) {
  const int nx = grid.num_points[0], nz = grid.num_points[2];
  std::vector<std::uint8_t> inside(grid.num_total_points(), 0);
  const auto signs = exact_normal_signs(mesh);
  for_each_line(mesh, grid, 2, signs, [&](std::size_t line, int i, int j, const std::vector<int>& crossed) {
    if (crossed.empty()) return;
    const double x = grid.coordinate(0, i), y = grid.coordinate(1, j);
    std::vector<std::uint8_t> toggle(static_cast<std::size_t>(nz) + 1, 0);
    for (int f : crossed) {
      const auto& t = mesh.faces[static_cast<std::size_t>(f)];
      const Vec3& va = mesh.vertices[static_cast<std::size_t>(t[0])];
      const Vec3& vb = mesh.vertices[static_cast<std::size_t>(t[1])];
      const Vec3& vc = mesh.vertices[static_cast<std::size_t>(t[2])];
      const Point3 pa(va.x(), va.y(), va.z()), pb(vb.x(), vb.y(), vb.z()), pc(vc.x(), vc.y(), vc.z());
      const auto& s = signs[static_cast<std::size_t>(f)];
      // Sign of n.(p - a) at p + (e, e^2, e^3) when n.(p - a) == 0: the first
      // nonzero of n_x, n_y, n_z (exact signs). n_z != 0 for crossed faces.
      const int tie = s[0] != 0 ? s[0] : (s[1] != 0 ? s[1] : s[2]);
      // p is above the plane (the crossing lies below p) iff n.(p - a) has the sign of n_z.
      const auto above = [&](int k) {
        const auto o = CGAL::orientation(pa, pb, pc, Point3(x, y, grid.coordinate(2, k)));
        const int side = o == CGAL::COPLANAR ? tie : static_cast<int>(o);
        return side == s[2];
      };
      // First k above the crossing (monotone in k): guess from the rounded
      // position, then walk with the exact predicate.
      const double z = crossing_position(mesh, static_cast<std::size_t>(f), 2, x, y);
      int k = grid.index_at_or_above(2, z);
      while (k > 0 && above(k - 1)) --k;
      while (k < nz && !above(k)) ++k;
      toggle[static_cast<std::size_t>(k)] ^= 1;
    }
    std::uint8_t parity = 0;
    for (int k = 0; k < nz; ++k) {
      parity ^= toggle[static_cast<std::size_t>(k)];
      inside[grid.index(i, j, k)] = parity;
    }
    (void)line;
    (void)nx;
  });
  return inside;
}

}  // namespace subfab::detail
