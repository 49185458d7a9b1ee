// SPDX-License-Identifier: GPL-3.0-or-later
#include "decompose/mark_triangle_cells.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Iso_cuboid_3.h>
#include <CGAL/Triangle_3.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "geometry/exact_normal_signs.h"
#include "geometry/triangle_meets_closed_box.h"
#include "subfab/core/parallel.h"

namespace subfab::detail {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;

//! Range of cells [lo, hi] along dim whose closed extent [coord(c), coord(c + 1)]
//! meets [min, max] (exact comparisons of the grid coordinates); empty when lo > hi.
std::array<int, 2> cell_range(const GridGeometry& grid, int dim, double min, double max) {
  const int num_cells = grid.num_points[static_cast<std::size_t>(dim)] - 1;
  // coord(c + 1) >= min  <=>  c + 1 >= index_at_or_above(min);  coord(c) <= max  <=>  c <= index_at_or_below(max).
  return {std::max(grid.index_at_or_above(dim, min) - 1, 0), std::min(grid.index_at_or_below(dim, max), num_cells - 1)};
}
}  // namespace

std::size_t num_grid_cells(const GridGeometry& grid) {
  std::size_t n = 1;
  for (int c = 0; c < 3; ++c) n *= static_cast<std::size_t>(std::max(grid.num_points[static_cast<std::size_t>(c)] - 1, 0));
  return n;
}

std::vector<std::uint16_t> mark_triangle_cells(const Mesh& mesh, const GridGeometry& grid, double overhang_sine,
                                               const std::vector<std::uint8_t>* allowed) {
  std::vector<std::uint16_t> flags(num_grid_cells(grid), 0);
  if (flags.empty()) return flags;
  const auto signs = facing_signs(mesh, overhang_sine, allowed);  // exact signs when neither is given
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
        // A zero-area triangle is tested as the segment or point it spans.
        // (All facing signs 0 can also mean an allowance above 1/sqrt(3) or a tolerance: ask the exact signs.)
        const bool degenerate =
            signs[f][0] == 0 && signs[f][1] == 0 && signs[f][2] == 0 &&
            ((overhang_sine <= 0.0 && !allowed) || exact_normal_signs(a, b, c) == std::array<std::int8_t, 3>{0, 0, 0});
        // A vertex in the closed cell (exact comparisons) decides without the full test.
        const auto has_vertex_in_cell = [&](int i, int j, int k) {
          const Vec3 cell_lo = grid.point(i, j, k), cell_hi = grid.point(i + 1, j + 1, k + 1);
          for (const Vec3* p : {&a, &b, &c})
            if ((p->array() >= cell_lo.array()).all() && (p->array() <= cell_hi.array()).all()) return true;
          return false;
        };
        for (int k = range[2][0]; k <= range[2][1]; ++k)
          for (int j = range[1][0]; j <= range[1][1]; ++j)
            for (int i = range[0][0]; i <= range[0][1]; ++i) {
              // A triangle whose bounding box lies in one closed cell meets it.
              if (!single && degenerate) {
                const Box3 cell{grid.point(i, j, k), grid.point(i + 1, j + 1, k + 1)};
                if (!triangle_meets_closed_box(a, b, c, cell)) continue;
              } else if (!single && !has_vertex_in_cell(i, j, k)) {
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
