// SPDX-License-Identifier: GPL-3.0-or-later
//! \file block_thickness.h
//! How thin a block is (issue 17, "no slivers"; thesis Section 4.3.4: the
//! snapping and merging of boxes exist so that no block is a sliver too thin
//! to mill or glue).
//!
//! Thickness along a unit axis u: the MEAN CHORD LENGTH of the solid along
//! u, i.e. its volume divided by the area of its projection along u counted
//! with multiplicity (a line entering the solid k times counts k times):
//!     t_u = V / (1/2 sum_f |u.n_f| A_f) = 2 V / sum_f |u.n_f| A_f
//! (n_f, A_f: unit normal and area of face f; for a closed surface every
//! line along u crosses it an even number of times, and half the crossings
//! weighted by area is that projected area). It is exact for prisms along
//! u: a box a x b x c has t_z = c, a plate of thickness e has t = e along its
//! normal whatever its outline. The block's thickness is the smallest t_u
//! over the three rows of its frame (the canonical frame its box was grown
//! in, where blocks come from axis-aligned boxes). It needs no distance
//! field and costs one pass over the faces.
#pragma once

#include <array>

#include <Eigen/Core>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! Result of block_thickness().
struct BlockThickness {
  double thickness = 0.0;               // min of `along` (model units; 0 for an empty or flat mesh)
  int thinnest_row = 2;                 // row of the frame realising it (0, 1, 2)
  Vec3 axis = Vec3::UnitZ();            // that row (unit, the mesh's coordinates)
  std::array<double, 3> along{};        // mean chord length along each row of the frame (model units)
};

//! The mean chord lengths of the closed solid `block` along the three rows
//! of `frame` (a rotation: input -> canonical coordinates, e.g. a block's
//! machine transform), and the smallest. A non-positive volume gives 0.
BlockThickness block_thickness(const Mesh& block, const Eigen::Matrix3d& frame = Eigen::Matrix3d::Identity());

}  // namespace subfab
