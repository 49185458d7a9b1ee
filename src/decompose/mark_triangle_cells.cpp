// SPDX-License-Identifier: GPL-3.0-or-later
#include "decompose/mark_triangle_cells.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Iso_cuboid_3.h>
#include <CGAL/Triangle_3.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "decompose/exact_normal_signs.h"
#include "subfab/core/parallel.h"

namespace subfab::detail {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;

//! Range of cells [lo, hi] along dim whose closed extent meets [min, max]
//! (exact comparisons of the grid coordinates); empty when lo > hi.
std::array<int, 2> cell_range(const GridGeometry& grid, int dim, double min, double max) {
  const int num_cells = grid.num_points[static_cast<std::size_t>(dim)] - 1;
  // Cell c spans [coord(c), coord(c + 1)]: it meets [min, max] iff
  // coord(c + 1) >= min and coord(c) <= max.
  int lo = static_cast<int>(std::clamp(std::floor((min - grid.origin[dim]) / grid.spacing), 0.0, double(num_cells)));
  while (lo > 0 && grid.coordinate(dim, lo) >= min) --lo;
  while (lo < num_cells && grid.coordinate(dim, lo + 1) < min) ++lo;
  int hi = static_cast<int>(std::clamp(std::floor((max - grid.origin[dim]) / grid.spacing), -1.0, double(num_cells - 1)));
  while (hi < num_cells - 1 && grid.coordinate(dim, hi + 1) <= max) ++hi;
  while (hi >= 0 && grid.coordinate(dim, hi) > max) --hi;
  return {lo, hi};
}
}  // namespace

std::size_t num_grid_cells(const GridGeometry& grid) {
  std::size_t n = 1;
  for (int c = 0; c < 3; ++c) n *= static_cast<std::size_t>(std::max(grid.num_points[static_cast<std::size_t>(c)] - 1, 0));
  return n;
}

std::vector<std::uint16_t> mark_triangle_cells(const Mesh& mesh, const GridGeometry& grid) {
  std::vector<std::uint16_t> flags(num_grid_cells(grid), 0);
  if (flags.empty()) return flags;
  const auto signs = exact_normal_signs(mesh);
  parallel_for(
      0, mesh.num_faces(),
      [&](std::size_t f) {
        std::uint16_t bits = 0;
        for (int c = 0; c < 3; ++c) {
          const int s = signs[f][static_cast<std::size_t>(c)];
          bits |= s < 0 ? cell_flag_negative(c) : (s > 0 ? cell_flag_positive(c) : cell_flag_zero(c));
        }
        const auto& t = mesh.faces[f];
        const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
        const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
        const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
        const Vec3 lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
        std::array<std::array<int, 2>, 3> range;
        for (int d = 0; d < 3; ++d) {
          range[static_cast<std::size_t>(d)] = cell_range(grid, d, lo[d], hi[d]);
          if (range[static_cast<std::size_t>(d)][0] > range[static_cast<std::size_t>(d)][1]) return;
        }
        const bool single = range[0][0] == range[0][1] && range[1][0] == range[1][1] && range[2][0] == range[2][1];
        const Kernel::Triangle_3 triangle(Point3(a.x(), a.y(), a.z()), Point3(b.x(), b.y(), b.z()),
                                          Point3(c.x(), c.y(), c.z()));
        for (int k = range[2][0]; k <= range[2][1]; ++k)
          for (int j = range[1][0]; j <= range[1][1]; ++j)
            for (int i = range[0][0]; i <= range[0][1]; ++i) {
              // A triangle whose bounding box lies in one closed cell meets it.
              if (!single) {
                const Kernel::Iso_cuboid_3 cell(Point3(grid.coordinate(0, i), grid.coordinate(1, j), grid.coordinate(2, k)),
                                                Point3(grid.coordinate(0, i + 1), grid.coordinate(1, j + 1),
                                                       grid.coordinate(2, k + 1)));
                if (!CGAL::do_intersect(triangle, cell)) continue;
              }
              std::atomic_ref<std::uint16_t> cell_flags(flags[cell_index(grid, i, j, k)]);
              cell_flags.fetch_or(bits, std::memory_order_relaxed);
            }
      },
      256);
  return flags;
}

}  // namespace subfab::detail
