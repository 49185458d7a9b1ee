// SPDX-License-Identifier: GPL-3.0-or-later
//! \file classify_grid_points.h
//! Exact inside/outside classification of the points of a regular grid, and
//! the crossings of the grid lines with the surface (thesis Section 4.3.2:
//! the fields need the inside of the solid for the height limit; the authors
//! voted with 3 random rays, we count exact crossings).
//!
//! Rule (simulation of simplicity): a grid point p is classified as the point
//! p + (e, e^2, e^3) for an infinitesimal e > 0. Along the grid line through p
//! parallel to z, a triangle is crossed iff the perturbed line meets it (exact
//! 2D orientation predicates, ties broken by the perturbation, so a line
//! through an edge or a vertex crosses exactly one of the triangles around
//! it); a crossing lies below p iff the perturbed p is above the triangle's
//! plane (exact 3D orientation, ties broken by the perturbation). p is inside
//! iff an odd number of crossings lies below it. Triangles parallel to the line
//! are never crossed. Points exactly on the surface are therefore inside or
//! outside as the point infinitesimally beside them, consistently.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "subfab/decompose/compute_field.h"
#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! The crossings of all grid lines parallel to dimension `dim` with the
//! surface. Line (a, b) passes through the points with index a along
//! u = (dim + 1) % 3 and b along v = (dim + 2) % 3; its number is a + n_u * b.
struct LineCrossings {
  int dim = 2;
  std::array<int, 2> num_lines{0, 0};  // n_u, n_v
  std::vector<std::size_t> offsets;    // line l's crossings: positions[offsets[l] .. offsets[l + 1])
  std::vector<double> positions;       // coordinate along dim (model units, rounded), ascending per line
};

//! Crossings of the grid lines parallel to `dim` (0, 1, 2) with the mesh,
//! found with the exact perturbed point-in-triangle test above. Positions are
//! rounded double evaluations of the plane equation. Parallel over lines;
//! deterministic.
LineCrossings compute_line_crossings(const Mesh& mesh, const GridGeometry& grid, int dim);

//! Exact inside (1) / outside (0) of every grid point, indexed by
//! grid.index(i, j, k), by the rule in the file comment. Requires a closed
//! mesh (otherwise parity is meaningless). Parallel over z-lines; deterministic.
std::vector<std::uint8_t> classify_grid_points(const Mesh& mesh, const GridGeometry& grid);

}  // namespace subfab::detail
