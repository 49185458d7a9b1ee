// SPDX-License-Identifier: GPL-3.0-or-later
//! \file classify_grid_points.h
//! Exact inside/outside classification of the points of a regular grid
//! against a closed triangle mesh (thesis Sections 3.3.1 and 4.3.1: the
//! lattice / grid signs). Shared by the unfolding lattice (src/unfold) and
//! the decomposition grid (src/decompose).
//!
//! Method: one vertical line (along z) per grid column; every triangle whose
//! xy-projection contains the column is crossed, and the crossing is ordered
//! against the grid points of the column, all with exact CGAL predicates
//! (Epick orientation_2 / orientation). The same line/triangle test along x,
//! y or z gives the crossings the decomposition needs for its height limit
//! (compute_line_crossings(); Section 4.3.2: the authors voted with 3 random
//! rays, we count exact crossings). Degenerate cases (a column through a
//! mesh edge or vertex, a grid point exactly on the surface) are decided by
//! symbolic perturbation: every grid point p is classified as the point
//! p + (e, e^2, e^3) for an infinitesimal e > 0, which is never on the
//! surface. The result is exact, deterministic and independent of the
//! thread count.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! A regular grid of points: point (i, j, k) is at
//! origin + spacing * (i, j, k), 0 <= i < size[0] (same for j, k).
//! Points are stored x-fastest: index = i + size[0] * (j + size[1] * k).
struct GridPoints {
  Vec3 origin = Vec3::Zero();       // position of point (0, 0, 0), model units
  double spacing = 1.0;             // distance between neighbouring points, model units
  std::array<int, 3> size{0, 0, 0};  // number of points along x, y, z

  std::size_t num_points() const {
    return static_cast<std::size_t>(size[0]) * static_cast<std::size_t>(size[1]) *
           static_cast<std::size_t>(size[2]);
  }
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(size[0]) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(size[1]) * static_cast<std::size_t>(k));
  }
  //! Coordinate of grid plane `i` along `axis` (the exact double every
  //! predicate uses).
  double coordinate(int axis, int i) const { return origin[axis] + spacing * i; }
  Vec3 point(int i, int j, int k) const {
    return Vec3(coordinate(0, i), coordinate(1, j), coordinate(2, k));
  }
};

//! The crossings of the grid lines parallel to one dimension with a surface.
//! Line (a, b) passes through the grid points with index a along
//! u = (dim + 1) % 3 and b along v = (dim + 2) % 3; its number is
//! a + size[u] * b.
struct LineCrossings {
  int dim = 2;                          // the lines are parallel to this dimension (0, 1, 2)
  std::array<int, 2> num_lines{0, 0};   // size[u], size[v]
  std::vector<std::size_t> offsets;     // line l's crossings: positions[offsets[l] .. offsets[l + 1])
  std::vector<double> positions;        // coordinate along dim (model units, rounded), ascending per line
};

//! Crossings of every grid line parallel to `dim` with the faces of `mesh`.
//! Whether a line crosses a face is decided exactly, with the same symbolic
//! perturbation as classify_grid_points() (so a line through an edge or a
//! vertex crosses exactly one of the faces around it, and faces parallel to
//! the line are never crossed); the position of each crossing is the rounded
//! intersection with the face's plane (used for distances, never for
//! inside/outside). Parallel over lines; deterministic.
//! 	hrow InvalidArgumentError when the grid is empty, the spacing is not > 0
//!        or dim is not 0, 1 or 2.
LineCrossings compute_line_crossings(const Mesh& mesh, const GridPoints& grid, int dim);

//! Winding number of `mesh` around every point of `grid` (a point infinitely
//! close to it, see the file comment): for a closed, outward-oriented solid,
//! 1 inside and 0 outside (-1 inside an inward-oriented one).
//! \param mesh closed triangle mesh (faces CCW from outside); open meshes give
//!             meaningless but still deterministic numbers.
//! \return grid.num_points() winding numbers, indexed like GridPoints::index().
//! \throw InvalidArgumentError when the grid is empty or spacing is not > 0.
std::vector<std::int32_t> classify_grid_points(const Mesh& mesh, const GridPoints& grid);

}  // namespace subfab
