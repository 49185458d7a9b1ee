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
//! (Epick orientation_2 / orientation). Degenerate cases (a column through a
//! mesh edge or vertex, a grid point exactly on the surface) are decided by
//! symbolic perturbation: every grid point p is classified as the point
//! p + (e, e^2, e^3) for an infinitesimal e > 0, which is never on the
//! surface. The result is exact, deterministic and independent of the
//! thread count.
#pragma once

#include <array>
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

//! Winding number of `mesh` around every point of `grid` (a point infinitely
//! close to it, see the file comment): for a closed, outward-oriented solid,
//! 1 inside and 0 outside (-1 inside an inward-oriented one).
//! \param mesh closed triangle mesh (faces CCW from outside); open meshes give
//!             meaningless but still deterministic numbers.
//! \return grid.num_points() winding numbers, indexed like GridPoints::index().
//! \throw InvalidArgumentError when the grid is empty or spacing is not > 0.
std::vector<std::int32_t> classify_grid_points(const Mesh& mesh, const GridPoints& grid);

}  // namespace subfab
