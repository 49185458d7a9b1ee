// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/geometry/classify_grid_points.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;
using Point3 = Kernel::Point_3;

int sign_of(CGAL::Orientation o) { return o == CGAL::POSITIVE ? 1 : (o == CGAL::NEGATIVE ? -1 : 0); }

//! The plane a line parallel to `dim` is projected on, with its two
//! coordinates in increasing dimension order (p < q): the perturbation
//! (e, e^2, e^3) moves a point by e^(p+1) along p and e^(q+1) along q, so p
//! dominates.
struct Projection {
  int dim = 2;
  int p = 0;
  int q = 1;
};

Projection projection_along(int dim) {
  const int a = (dim + 1) % 3, b = (dim + 2) % 3;
  return {dim, std::min(a, b), std::max(a, b)};
}

//! Exact sign of orient2d(a, b, x + perturbation) in the projection plane,
//! x = (xp, xq): orient2d(a, b, x) - (b_q - a_q) e_p + (b_p - a_p) e_q with
//! e_p >> e_q > 0. Never 0 unless a and b coincide in the projection.
int perturbed_orient(const Vec3& a, const Vec3& b, const Projection& pr, double xp, double xq) {
  const int s = sign_of(CGAL::orientation(Point2(a[pr.p], a[pr.q]), Point2(b[pr.p], b[pr.q]), Point2(xp, xq)));
  if (s != 0) return s;
  if (b[pr.q] != a[pr.q]) return b[pr.q] > a[pr.q] ? -1 : 1;
  return b[pr.p] > a[pr.p] ? 1 : (b[pr.p] < a[pr.p] ? -1 : 0);
}

//! One triangle with the exact signs of its normal's components.
struct LineTriangle {
  Vec3 a, b, c;
  std::array<int, 3> normal_sign{0, 0, 0};  // signs of the x, y, z components of (b - a) x (c - a)

  //! Sign of the triangle's orientation in the projection plane (p, q).
  int projected_sign(const Projection& pr) const {
    // orient(p, q) is +n_dim for the cyclic pair (dim+1, dim+2), -n_dim otherwise.
    const int s = normal_sign[static_cast<std::size_t>(pr.dim)];
    return pr.p == (pr.dim + 1) % 3 ? s : -s;
  }
};

std::vector<LineTriangle> prepare_triangles(const Mesh& mesh) {
  std::vector<LineTriangle> tris(mesh.faces.size());
  parallel_for(
      0, tris.size(),
      [&](std::size_t f) {
        LineTriangle& t = tris[f];
        const auto& face = mesh.faces[f];
        t.a = mesh.vertices[static_cast<std::size_t>(face[0])];
        t.b = mesh.vertices[static_cast<std::size_t>(face[1])];
        t.c = mesh.vertices[static_cast<std::size_t>(face[2])];
        for (int d = 0; d < 3; ++d) {
          const int u = (d + 1) % 3, v = (d + 2) % 3;
          t.normal_sign[static_cast<std::size_t>(d)] = sign_of(CGAL::orientation(
              Point2(t.a[u], t.a[v]), Point2(t.b[u], t.b[v]), Point2(t.c[u], t.c[v])));
        }
      },
      1024);
  return tris;
}

void check_grid(const GridPoints& grid) {
  if (grid.size[0] <= 0 || grid.size[1] <= 0 || grid.size[2] <= 0)
    throw InvalidArgumentError("classify_grid_points: the grid has no points");
  if (!(grid.spacing > 0) || !std::isfinite(grid.spacing))
    throw InvalidArgumentError("classify_grid_points: grid spacing must be a positive number");
}

//! Calls fn(line, a, b, crossed) for every grid line parallel to `dim`, in
//! parallel, where line = a + size[u] * b (u = (dim + 1) % 3, v = (dim + 2) % 3)
//! and `crossed` lists, in increasing order, the faces the perturbed line
//! crosses (exact).
template <typename Fn>
void for_each_line(const std::vector<LineTriangle>& tris, const GridPoints& grid, int dim, const Fn& fn) {
  const Projection pr = projection_along(dim);
  const int u = (dim + 1) % 3, v = (dim + 2) % 3;
  const int nu = grid.size[static_cast<std::size_t>(u)], nv = grid.size[static_cast<std::size_t>(v)];
  const std::size_t num_lines = static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv);
  const std::size_t num_faces = tris.size();

  // Candidate lines of each triangle: its bounding box across the lines,
  // widened by one line on each side (the exact test below decides).
  auto line_range = [&](double lo, double hi, int axis) {
    const int n = grid.size[static_cast<std::size_t>(axis)];
    const double o = grid.origin[axis];
    const double a = std::max(std::floor((lo - o) / grid.spacing) - 1.0, 0.0);
    const double b = std::min(std::ceil((hi - o) / grid.spacing) + 1.0, static_cast<double>(n - 1));
    return std::pair<int, int>(static_cast<int>(a), static_cast<int>(b));
  };
  std::vector<std::array<int, 4>> ranges(num_faces);
  parallel_for(
      0, num_faces,
      [&](std::size_t f) {
        const LineTriangle& t = tris[f];
        if (t.normal_sign[static_cast<std::size_t>(dim)] == 0) {  // parallel to the lines: never crossed
          ranges[f] = {0, -1, 0, -1};
          return;
        }
        const auto [a0, a1] = line_range(std::min({t.a[u], t.b[u], t.c[u]}), std::max({t.a[u], t.b[u], t.c[u]}), u);
        const auto [b0, b1] = line_range(std::min({t.a[v], t.b[v], t.c[v]}), std::max({t.a[v], t.b[v], t.c[v]}), v);
        ranges[f] = {a0, a1, b0, b1};
      },
      1024);
  // Bucket triangles per line (counting sort, deterministic order).
  std::vector<std::size_t> start(num_lines + 1, 0);
  for (const auto& r : ranges)
    for (int b = r[2]; b <= r[3]; ++b)
      for (int a = r[0]; a <= r[1]; ++a) ++start[static_cast<std::size_t>(a) + static_cast<std::size_t>(nu) * b + 1];
  for (std::size_t l = 0; l < num_lines; ++l) start[l + 1] += start[l];
  std::vector<int> bucket(start[num_lines]);
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t f = 0; f < num_faces; ++f) {
      const auto& r = ranges[f];
      for (int b = r[2]; b <= r[3]; ++b)
        for (int a = r[0]; a <= r[1]; ++a)
          bucket[fill[static_cast<std::size_t>(a) + static_cast<std::size_t>(nu) * b]++] = static_cast<int>(f);
    }
  }

  parallel_for(
      0, num_lines,
      [&](std::size_t line) {
        const int a = static_cast<int>(line % static_cast<std::size_t>(nu));
        const int b = static_cast<int>(line / static_cast<std::size_t>(nu));
        Vec3 x = Vec3::Zero();
        x[u] = grid.coordinate(u, a);
        x[v] = grid.coordinate(v, b);
        std::vector<int> crossed;
        for (std::size_t e = start[line]; e < start[line + 1]; ++e) {
          const LineTriangle& t = tris[static_cast<std::size_t>(bucket[e])];
          const int s = t.projected_sign(pr);
          if (perturbed_orient(t.a, t.b, pr, x[pr.p], x[pr.q]) != s ||
              perturbed_orient(t.b, t.c, pr, x[pr.p], x[pr.q]) != s ||
              perturbed_orient(t.c, t.a, pr, x[pr.p], x[pr.q]) != s)
            continue;
          crossed.push_back(bucket[e]);
        }
        fn(line, a, b, crossed);
      },
      16);
}

//! Rounded coordinate along `dim` where the line through x (x[dim] ignored)
//! meets the plane of t (t is not parallel to the line).
double crossing_position(const LineTriangle& t, int dim, const Vec3& x) {
  const int u = (dim + 1) % 3, v = (dim + 2) % 3;
  const Vec3 n = (t.b - t.a).cross(t.c - t.a);
  return t.a[dim] - (n[u] * (x[u] - t.a[u]) + n[v] * (x[v] - t.a[v])) / n[dim];
}

// Exact sign of orient3d(a, b, c, p + (e, e^2, e^3)): positive when the
// perturbed point is on the side the normal (b - a) x (c - a) points to.
int perturbed_orient_3d(const LineTriangle& t, const Vec3& p) {
  const int s = sign_of(CGAL::orientation(Point3(t.a.x(), t.a.y(), t.a.z()), Point3(t.b.x(), t.b.y(), t.b.z()),
                                          Point3(t.c.x(), t.c.y(), t.c.z()), Point3(p.x(), p.y(), p.z())));
  if (s != 0) return s;
  for (int d = 0; d < 3; ++d)
    if (t.normal_sign[static_cast<std::size_t>(d)] != 0) return t.normal_sign[static_cast<std::size_t>(d)];
  return 0;
}

}  // namespace

LineCrossings compute_line_crossings(const Mesh& mesh, const GridPoints& grid, int dim) {
  check_grid(grid);
  if (dim < 0 || dim > 2) throw InvalidArgumentError("compute_line_crossings: dimension must be 0, 1 or 2");
  const int u = (dim + 1) % 3, v = (dim + 2) % 3;
  LineCrossings result;
  result.dim = dim;
  result.num_lines = {grid.size[static_cast<std::size_t>(u)], grid.size[static_cast<std::size_t>(v)]};
  const std::size_t num_lines =
      static_cast<std::size_t>(result.num_lines[0]) * static_cast<std::size_t>(result.num_lines[1]);
  const std::vector<LineTriangle> tris = prepare_triangles(mesh);
  std::vector<std::vector<double>> per_line(num_lines);
  for_each_line(tris, grid, dim, [&](std::size_t line, int a, int b, const std::vector<int>& crossed) {
    Vec3 x = Vec3::Zero();
    x[u] = grid.coordinate(u, a);
    x[v] = grid.coordinate(v, b);
    auto& out = per_line[line];
    out.reserve(crossed.size());
    for (int f : crossed) out.push_back(crossing_position(tris[static_cast<std::size_t>(f)], dim, x));
    std::sort(out.begin(), out.end());
  });
  result.offsets.assign(num_lines + 1, 0);
  for (std::size_t l = 0; l < num_lines; ++l) result.offsets[l + 1] = result.offsets[l] + per_line[l].size();
  result.positions.reserve(result.offsets[num_lines]);
  for (const auto& line : per_line) result.positions.insert(result.positions.end(), line.begin(), line.end());
  return result;
}

std::vector<std::int32_t> classify_grid_points(const Mesh& mesh, const GridPoints& grid) {
  check_grid(grid);
  const int nz = grid.size[2];
  const std::vector<LineTriangle> tris = prepare_triangles(mesh);
  std::vector<std::int32_t> winding(grid.num_points(), 0);
  for_each_line(tris, grid, 2, [&](std::size_t, int i, int j, const std::vector<int>& crossed) {
    if (crossed.empty()) return;
    const double px = grid.coordinate(0, i), py = grid.coordinate(1, j);
    // delta[k]: sum of the crossings' signs whose first grid point above
    // them is k (k == nz: above the whole column).
    std::vector<std::int32_t> delta(static_cast<std::size_t>(nz) + 1, 0);
    for (int f : crossed) {
      const LineTriangle& t = tris[static_cast<std::size_t>(f)];
      const int s = t.normal_sign[2];
      // First grid point above the crossing: a floating-point guess, then
      // an exact walk (the perturbed side is monotone along the column).
      auto above = [&](int k) { return perturbed_orient_3d(t, Vec3(px, py, grid.coordinate(2, k))) == s; };
      const double zc = crossing_position(t, 2, Vec3(px, py, 0.0));
      int k = 0;
      if (std::isfinite(zc))
        k = static_cast<int>(std::clamp(std::floor((zc - grid.origin.z()) / grid.spacing), 0.0, static_cast<double>(nz)));
      while (k > 0 && above(k - 1)) --k;
      while (k < nz && !above(k)) ++k;
      // Seen from a point below the crossing, the upward ray leaves the
      // solid through an up-facing triangle: winding +1.
      delta[static_cast<std::size_t>(k)] += s;
    }
    std::int32_t w = delta[static_cast<std::size_t>(nz)];
    for (int k = nz - 1; k >= 0; --k) {
      // Point k gets every crossing whose first point above is > k.
      winding[grid.index(i, j, k)] = w;
      w += delta[static_cast<std::size_t>(k)];
    }
  });
  return winding;
}

}  // namespace subfab
