// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/compute_field.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "decompose/mark_triangle_cells.h"
#include "subfab/geometry/classify_grid_points.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

//! Largest grid we build (points); beyond it the user should coarsen the grid.
constexpr double kMaxGridPoints = 2147483647.0;

//! Bits of the per-point "too deep" mask, one per axis_index.
constexpr std::uint8_t deep_bit(Axis a) { return static_cast<std::uint8_t>(1u << axis_index(a)); }

//! The field grid as the exact classifier of src/checks sees it (same
//! points, same coordinates).
GridPoints as_grid_points(const GridGeometry& grid) {
  return GridPoints{.origin = grid.origin, .spacing = grid.spacing, .size = grid.num_points};
}

//! For every grid point, bit axis_index(a) set when the point is inside and
//! the ray along a leaves the solid only beyond max_height. Inside/outside
//! and the crossings are exact (classify_grid_points, compute_line_crossings).
std::vector<std::uint8_t> mark_too_deep(const Mesh& mesh, const GridGeometry& grid, double max_height) {
  const GridPoints points = as_grid_points(grid);
  const std::vector<std::int32_t> inside = classify_grid_points(mesh, points);
  std::vector<std::uint8_t> deep(grid.num_total_points(), 0);
  for (int dim = 0; dim < 3; ++dim) {
    const LineCrossings lines = compute_line_crossings(mesh, points, dim);
    const int u = (dim + 1) % 3, v = (dim + 2) % 3;
    const int nu = lines.num_lines[0];
    const int n = grid.num_points[static_cast<std::size_t>(dim)];
    const std::size_t num_lines = static_cast<std::size_t>(lines.num_lines[0]) * static_cast<std::size_t>(lines.num_lines[1]);
    const Axis pos = static_cast<Axis>(2 * dim), neg = static_cast<Axis>(2 * dim + 1);
    parallel_for(
        0, num_lines,
        [&](std::size_t line) {
          const double* begin = lines.positions.data() + lines.offsets[line];
          const double* end = lines.positions.data() + lines.offsets[line + 1];
          if (begin == end) return;
          std::array<int, 3> idx{};
          idx[static_cast<std::size_t>(u)] = static_cast<int>(line % static_cast<std::size_t>(nu));
          idx[static_cast<std::size_t>(v)] = static_cast<int>(line / static_cast<std::size_t>(nu));
          for (int t = 0; t < n; ++t) {
            idx[static_cast<std::size_t>(dim)] = t;
            const std::size_t p = grid.index(idx[0], idx[1], idx[2]);
            if (inside[p] <= 0) continue;
            const double x = grid.coordinate(dim, t);
            // Exit upwards: first crossing at or above x; downwards: last at or below.
            const double* up = std::lower_bound(begin, end, x);
            const double* down = std::upper_bound(begin, end, x);
            const double exit_up = up == end ? 0.0 : *up - x;
            const double exit_down = down == begin ? 0.0 : x - *(down - 1);
            if (exit_up > max_height) deep[p] |= deep_bit(pos);
            if (exit_down > max_height) deep[p] |= deep_bit(neg);
          }
        },
        16);
  }
  return deep;
}

}  // namespace

int GridGeometry::index_at_or_below(int dim, double x) const {
  const int n = num_points[static_cast<std::size_t>(dim)];
  const double guess = std::floor((x - origin[dim]) / spacing);
  int i = static_cast<int>(std::clamp(guess, -1.0, static_cast<double>(n - 1)));  // NaN-free for finite x
  while (i < n - 1 && coordinate(dim, i + 1) <= x) ++i;
  while (i >= 0 && coordinate(dim, i) > x) --i;
  return i;
}

int GridGeometry::index_at_or_above(int dim, double x) const {
  const int n = num_points[static_cast<std::size_t>(dim)];
  const double guess = std::ceil((x - origin[dim]) / spacing);
  int i = static_cast<int>(std::clamp(guess, 0.0, static_cast<double>(n)));
  while (i > 0 && coordinate(dim, i - 1) >= x) --i;
  while (i < n && coordinate(dim, i) < x) ++i;
  return i;
}

GridGeometry make_grid(const Mesh& mesh, double grid_factor) {
  if (!(grid_factor > 0) || !std::isfinite(grid_factor))
    throw InvalidArgumentError("grid factor must be a positive number (got " + std::to_string(grid_factor) + ")");
  if (mesh.empty()) throw InvalidMeshError("cannot build a grid over a mesh with no faces");
  const BoundingBox box = bounding_box(mesh);
  const double edge = average_edge_length(mesh);
  const double spacing = edge * grid_factor;
  if (!(spacing > 0) || !std::isfinite(spacing) || box.diagonal() <= 0)
    throw InvalidMeshError("cannot build a grid: the mesh has zero extent or zero average edge length");
  GridGeometry grid;
  grid.spacing = spacing;
  double total = 1;
  for (int c = 0; c < 3; ++c) {
    // Cells needed to span the box, plus one padding cell on each side.
    const double cells = std::ceil((box.max[c] - box.min[c]) / spacing);
    total *= cells + 3;
    if (total > kMaxGridPoints) {
      std::ostringstream msg;
      msg << "the field grid would be too large (more than 2^31 points at spacing " << spacing
          << "); use a larger grid factor than " << grid_factor;
      throw InvalidArgumentError(msg.str());
    }
    grid.num_points[static_cast<std::size_t>(c)] = static_cast<int>(cells) + 3;
    grid.origin[c] = box.min[c] - spacing;
    // Rounding may leave the last point short of max + spacing: add points until it is not.
    while (grid.coordinate(c, grid.num_points[static_cast<std::size_t>(c)] - 1) < box.max[c] + spacing)
      ++grid.num_points[static_cast<std::size_t>(c)];
  }
  if (static_cast<double>(grid.num_total_points()) > kMaxGridPoints)
    throw InvalidArgumentError("the field grid would be too large; use a larger grid factor");
  return grid;
}

void HeightField::build_prefix_sums() {
  const int nx = grid.num_points[0], ny = grid.num_points[1], nz = grid.num_points[2];
  const std::size_t sx = static_cast<std::size_t>(nx) + 1, sy = static_cast<std::size_t>(ny) + 1,
                    sz = static_cast<std::size_t>(nz) + 1;
  prefix_forbidden.assign(sx * sy * sz, 0);
  prefix_good.assign(sx * sy * sz, 0);
  const auto at = [&](std::size_t i, std::size_t j, std::size_t k) { return i + sx * (j + sy * k); };
  // Values, then running sums along x (per (j, k) row), y, z.
  parallel_for(0, static_cast<std::size_t>(nz), [&](std::size_t k) {
    for (int j = 0; j < ny; ++j) {
      std::uint32_t run_f = 0, run_g = 0;
      for (int i = 0; i < nx; ++i) {
        const FieldValue value = values[grid.index(i, j, static_cast<int>(k))];
        run_f += value == FieldValue::Forbidden ? 1u : 0u;
        run_g += value == FieldValue::Good ? 1u : 0u;
        const std::size_t e = at(static_cast<std::size_t>(i) + 1, static_cast<std::size_t>(j) + 1, k + 1);
        prefix_forbidden[e] = run_f;
        prefix_good[e] = run_g;
      }
    }
  });
  parallel_for(1, sz, [&](std::size_t k) {
    for (std::size_t j = 2; j < sy; ++j)
      for (std::size_t i = 1; i < sx; ++i) {
        prefix_forbidden[at(i, j, k)] += prefix_forbidden[at(i, j - 1, k)];
        prefix_good[at(i, j, k)] += prefix_good[at(i, j - 1, k)];
      }
  });
  parallel_for(1, sy, [&](std::size_t j) {
    for (std::size_t k = 2; k < sz; ++k)
      for (std::size_t i = 1; i < sx; ++i) {
        prefix_forbidden[at(i, j, k)] += prefix_forbidden[at(i, j, k - 1)];
        prefix_good[at(i, j, k)] += prefix_good[at(i, j, k - 1)];
      }
  });
}

namespace {
std::int64_t box_count(const std::vector<std::uint32_t>& table, const GridGeometry& grid,
                       const std::array<int, 3>& lo_in, const std::array<int, 3>& hi_in) {
  if (table.empty()) return 0;
  std::array<std::size_t, 3> lo{}, hi{};  // half-open [lo, hi) in table coordinates
  for (std::size_t c = 0; c < 3; ++c) {
    const int l = std::max(lo_in[c], 0);
    const int h = std::min(hi_in[c], grid.num_points[c] - 1);
    if (l > h) return 0;
    lo[c] = static_cast<std::size_t>(l);
    hi[c] = static_cast<std::size_t>(h) + 1;
  }
  const std::size_t sx = static_cast<std::size_t>(grid.num_points[0]) + 1;
  const std::size_t sy = static_cast<std::size_t>(grid.num_points[1]) + 1;
  const auto at = [&](std::size_t i, std::size_t j, std::size_t k) { return table[i + sx * (j + sy * k)]; };
  // Inclusion-exclusion modulo 2^32: exact since the true count is below 2^32.
  const std::uint32_t count = at(hi[0], hi[1], hi[2]) - at(lo[0], hi[1], hi[2]) - at(hi[0], lo[1], hi[2]) -
                              at(hi[0], hi[1], lo[2]) + at(lo[0], lo[1], hi[2]) + at(lo[0], hi[1], lo[2]) +
                              at(hi[0], lo[1], lo[2]) - at(lo[0], lo[1], lo[2]);
  return static_cast<std::int64_t>(count);
}
}  // namespace

std::int64_t HeightField::count_forbidden(const std::array<int, 3>& lo, const std::array<int, 3>& hi) const {
  return box_count(prefix_forbidden, grid, lo, hi);
}

std::int64_t HeightField::count_good(const std::array<int, 3>& lo, const std::array<int, 3>& hi) const {
  return box_count(prefix_good, grid, lo, hi);
}

std::array<HeightField, 6> compute_fields(const Mesh& mesh, const FieldOptions& options) {
  return compute_fields(mesh, make_grid(mesh, options.grid_factor), options);
}

std::array<HeightField, 6> compute_fields(const Mesh& mesh, const GridGeometry& grid, const FieldOptions& options) {
  if (std::isnan(options.max_height) || options.max_height <= 0)
    throw InvalidArgumentError("maximum block height must be positive (got " + std::to_string(options.max_height) + ")");
  if (grid.num_points[0] < 2 || grid.num_points[1] < 2 || grid.num_points[2] < 2 || !(grid.spacing > 0))
    throw InvalidArgumentError("field grid needs at least 2 points per axis and a positive spacing");
  if (options.progress) {
    std::ostringstream msg;
    msg << "field grid " << grid.num_points[0] << " x " << grid.num_points[1] << " x " << grid.num_points[2]
        << " points, spacing " << grid.spacing;
    options.progress->info(msg.str());
  }
  const int nx = grid.num_points[0], ny = grid.num_points[1], nz = grid.num_points[2];

  const std::vector<std::uint16_t> cell_flags =
      detail::mark_triangle_cells(mesh, grid, overhang_sine(options.max_overhang_deg), options.allowed_overhangs);
  std::vector<std::uint8_t> deep;
  if (std::isfinite(options.max_height)) deep = mark_too_deep(mesh, grid, options.max_height);

  std::array<HeightField, 6> fields;
  for (Axis a : kAllAxes) {
    HeightField& field = fields[static_cast<std::size_t>(axis_index(a))];
    field.axis = a;
    field.grid = grid;
    field.values.assign(grid.num_total_points(), FieldValue::Free);
  }
  // Per point: OR of the flags of the (up to) 8 cells around it, then the value per axis.
  parallel_for(0, static_cast<std::size_t>(nz), [&](std::size_t kk) {
    const int k = static_cast<int>(kk);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        std::uint16_t bits = 0;
        for (int ck = std::max(k - 1, 0); ck <= std::min(k, nz - 2); ++ck)
          for (int cj = std::max(j - 1, 0); cj <= std::min(j, ny - 2); ++cj)
            for (int ci = std::max(i - 1, 0); ci <= std::min(i, nx - 2); ++ci)
              bits |= cell_flags[detail::cell_index(grid, ci, cj, ck)];
        const std::size_t p = grid.index(i, j, k);
        const std::uint8_t deep_bits = deep.empty() ? 0 : deep[p];
        if (bits == 0 && deep_bits == 0) continue;
        for (Axis a : kAllAxes) {
          const int c = axis_dimension(a);
          const bool positive = axis_sign(a) > 0;
          const std::uint16_t away = positive ? detail::cell_flag_negative(c) : detail::cell_flag_positive(c);
          const std::uint16_t facing = static_cast<std::uint16_t>(
              (positive ? detail::cell_flag_positive(c) : detail::cell_flag_negative(c)) | detail::cell_flag_zero(c));
          FieldValue value = FieldValue::Free;
          if ((bits & away) || (deep_bits & deep_bit(a)))
            value = FieldValue::Forbidden;
          else if (bits & facing)
            value = FieldValue::Good;
          fields[static_cast<std::size_t>(axis_index(a))].values[p] = value;
        }
      }
  });
  parallel_for(0, 6, [&](std::size_t a) { fields[a].build_prefix_sums(); });
  return fields;
}

}  // namespace subfab
