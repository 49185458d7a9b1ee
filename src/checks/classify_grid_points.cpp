// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/classify_grid_points.h"

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

// Exact sign of orient2d(a, b, q) for q = p + (e, e^2) in the xy-plane.
// orient2d(a, b, q) = orient2d(a, b, p) - (b.y - a.y) e + (b.x - a.x) e^2.
int perturbed_orient_xy(const Vec3& a, const Vec3& b, double px, double py) {
  const int s = sign_of(CGAL::orientation(Point2(a.x(), a.y()), Point2(b.x(), b.y()), Point2(px, py)));
  if (s != 0) return s;
  if (b.y() != a.y()) return b.y() > a.y() ? -1 : 1;
  return b.x() > a.x() ? 1 : (b.x() < a.x() ? -1 : 0);
}

// One triangle as the columns see it.
struct ColumnTriangle {
  Vec3 a, b, c;
  int xy_sign = 0;  // sign of the z component of (b - a) x (c - a)
  int nx_sign = 0;  // sign of its x component
  int ny_sign = 0;  // sign of its y component
};

// Exact sign of orient3d(a, b, c, p + (e, e^2, e^3)): positive when the
// perturbed point is on the side the normal (b - a) x (c - a) points to.
int perturbed_orient_3d(const ColumnTriangle& t, const Vec3& p) {
  const int s = sign_of(CGAL::orientation(Point3(t.a.x(), t.a.y(), t.a.z()), Point3(t.b.x(), t.b.y(), t.b.z()),
                                          Point3(t.c.x(), t.c.y(), t.c.z()), Point3(p.x(), p.y(), p.z())));
  if (s != 0) return s;
  if (t.nx_sign != 0) return t.nx_sign;
  if (t.ny_sign != 0) return t.ny_sign;
  return t.xy_sign;
}

}  // namespace

std::vector<std::int32_t> classify_grid_points(const Mesh& mesh, const GridPoints& grid) {
  if (grid.size[0] <= 0 || grid.size[1] <= 0 || grid.size[2] <= 0)
    throw InvalidArgumentError("classify_grid_points: the grid has no points");
  if (!(grid.spacing > 0) || !std::isfinite(grid.spacing))
    throw InvalidArgumentError("classify_grid_points: grid spacing must be a positive number");
  const int nx = grid.size[0], ny = grid.size[1], nz = grid.size[2];
  const std::size_t num_columns = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);

  // Prepare triangles (exact projected orientations) in parallel.
  const std::size_t num_faces = mesh.faces.size();
  std::vector<ColumnTriangle> tris(num_faces);
  parallel_for(
      0, num_faces,
      [&](std::size_t f) {
        ColumnTriangle& t = tris[f];
        const auto& face = mesh.faces[f];
        t.a = mesh.vertices[static_cast<std::size_t>(face[0])];
        t.b = mesh.vertices[static_cast<std::size_t>(face[1])];
        t.c = mesh.vertices[static_cast<std::size_t>(face[2])];
        t.xy_sign = sign_of(CGAL::orientation(Point2(t.a.x(), t.a.y()), Point2(t.b.x(), t.b.y()),
                                              Point2(t.c.x(), t.c.y())));
        t.nx_sign = sign_of(CGAL::orientation(Point2(t.a.y(), t.a.z()), Point2(t.b.y(), t.b.z()),
                                              Point2(t.c.y(), t.c.z())));
        t.ny_sign = sign_of(CGAL::orientation(Point2(t.a.z(), t.a.x()), Point2(t.b.z(), t.b.x()),
                                              Point2(t.c.z(), t.c.x())));
      },
      1024);

  // Candidate columns of each triangle: its xy bounding box widened by one
  // column on each side (the exact test below decides).
  auto column_range = [&](double lo, double hi, int axis, int n) {
    const double o = grid.origin[axis];
    double a = std::floor((lo - o) / grid.spacing) - 1.0;
    double b = std::ceil((hi - o) / grid.spacing) + 1.0;
    a = std::max(a, 0.0);
    b = std::min(b, static_cast<double>(n - 1));
    return std::pair<int, int>(static_cast<int>(a), static_cast<int>(b));
  };
  std::vector<std::array<int, 4>> ranges(num_faces);
  parallel_for(
      0, num_faces,
      [&](std::size_t f) {
        const ColumnTriangle& t = tris[f];
        if (t.xy_sign == 0) {
          ranges[f] = {0, -1, 0, -1};
          return;
        }
        const auto [i0, i1] = column_range(std::min({t.a.x(), t.b.x(), t.c.x()}),
                                           std::max({t.a.x(), t.b.x(), t.c.x()}), 0, nx);
        const auto [j0, j1] = column_range(std::min({t.a.y(), t.b.y(), t.c.y()}),
                                           std::max({t.a.y(), t.b.y(), t.c.y()}), 1, ny);
        ranges[f] = {i0, i1, j0, j1};
      },
      1024);
  // Bucket triangles per column (counting sort, deterministic order).
  std::vector<std::size_t> start(num_columns + 1, 0);
  for (std::size_t f = 0; f < num_faces; ++f) {
    const auto& r = ranges[f];
    for (int j = r[2]; j <= r[3]; ++j)
      for (int i = r[0]; i <= r[1]; ++i) ++start[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * j + 1];
  }
  for (std::size_t c = 0; c < num_columns; ++c) start[c + 1] += start[c];
  std::vector<int> bucket(start[num_columns]);
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t f = 0; f < num_faces; ++f) {
      const auto& r = ranges[f];
      for (int j = r[2]; j <= r[3]; ++j)
        for (int i = r[0]; i <= r[1]; ++i)
          bucket[fill[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * j]++] = static_cast<int>(f);
    }
  }

  std::vector<std::int32_t> winding(grid.num_points(), 0);
  parallel_for(
      0, num_columns,
      [&](std::size_t column) {
        const int i = static_cast<int>(column % static_cast<std::size_t>(nx));
        const int j = static_cast<int>(column / static_cast<std::size_t>(nx));
        const double px = grid.coordinate(0, i), py = grid.coordinate(1, j);
        // delta[k]: sum of the crossings' signs whose first grid point above
        // them is k (k == nz: above the whole column).
        std::vector<std::int32_t> delta(static_cast<std::size_t>(nz) + 1, 0);
        bool any = false;
        for (std::size_t b = start[column]; b < start[column + 1]; ++b) {
          const ColumnTriangle& t = tris[static_cast<std::size_t>(bucket[b])];
          const int s = t.xy_sign;
          if (perturbed_orient_xy(t.a, t.b, px, py) != s || perturbed_orient_xy(t.b, t.c, px, py) != s ||
              perturbed_orient_xy(t.c, t.a, px, py) != s)
            continue;
          // The column crosses the triangle. First grid point above the
          // crossing: start from a floating-point guess, then walk exactly.
          auto above = [&](int k) { return perturbed_orient_3d(t, Vec3(px, py, grid.coordinate(2, k))) == s; };
          const Vec3 n = (t.b - t.a).cross(t.c - t.a);
          const double zc = t.a.z() - (n.x() * (px - t.a.x()) + n.y() * (py - t.a.y())) / n.z();
          int k = 0;
          if (std::isfinite(zc)) {
            const double g = std::floor((zc - grid.origin.z()) / grid.spacing);
            k = static_cast<int>(std::clamp(g, 0.0, static_cast<double>(nz)));
          }
          while (k > 0 && above(k - 1)) --k;
          while (k < nz && !above(k)) ++k;
          // Seen from a point below the crossing, the upward ray leaves the
          // solid through an up-facing triangle: winding +1.
          delta[static_cast<std::size_t>(k)] += s;
          any = true;
        }
        if (!any) return;
        std::int32_t w = delta[static_cast<std::size_t>(nz)];
        for (int k = nz - 1; k >= 0; --k) {
          // Points k gets every crossing whose first point above is > k.
          winding[grid.index(i, j, k)] = w;
          w += delta[static_cast<std::size_t>(k)];
        }
      },
      16);
  return winding;
}

}  // namespace subfab
