// SPDX-License-Identifier: GPL-3.0-or-later
//! \file mark_triangle_cells.h
//! Which closed grid cells each triangle meets, and which way those triangles
//! face (thesis Section 4.3.2: the field is infinite at the corners of cells
//! containing triangles facing away from the milling direction).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "subfab/decompose/compute_field.h"
#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! Flag bits of a cell, for dimension c = 0, 1, 2: the cell meets a triangle
//! whose exact normal component n_c is negative / positive / zero (under an
//! overhang allowance s: its facing_signs() component).
constexpr std::uint16_t cell_flag_negative(int c) { return static_cast<std::uint16_t>(1u << (3 * c)); }
constexpr std::uint16_t cell_flag_positive(int c) { return static_cast<std::uint16_t>(1u << (3 * c + 1)); }
constexpr std::uint16_t cell_flag_zero(int c) { return static_cast<std::uint16_t>(1u << (3 * c + 2)); }

//! Number of cells of the grid: (nx - 1)(ny - 1)(nz - 1).
std::size_t num_grid_cells(const GridGeometry& grid);
//! Index of the cell whose lowest corner is point (i, j, k).
inline std::size_t cell_index(const GridGeometry& grid, int i, int j, int k) {
  return static_cast<std::size_t>(i) +
         static_cast<std::size_t>(grid.num_points[0] - 1) *
             (static_cast<std::size_t>(j) + static_cast<std::size_t>(grid.num_points[1] - 1) * static_cast<std::size_t>(k));
}

//! Per cell, the OR of the flags of every triangle meeting the closed cell
//! (exact triangle / box test, CGAL Epick). Parallel over triangles; the OR is
//! order independent, so the result does not depend on the thread count.
//! \param overhang_sine allowance s >= 0 of the facing signs (0: exact)
//! \param allowed optional per-face allowances of the facing signs (facing_signs())
std::vector<std::uint16_t> mark_triangle_cells(const Mesh& mesh, const GridGeometry& grid, double overhang_sine = 0.0,
                                               const std::vector<std::uint8_t>* allowed = nullptr);

}  // namespace subfab::detail
