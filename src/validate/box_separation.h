// SPDX-License-Identifier: GPL-3.0-or-later
//! \file box_separation.h
//! Private (validate, check 3): a cheap, rigorous bound of the overlap of two
//! blocks whose contact is not one plane. Blocks are carved from boxes of
//! one frame, and a later block is cut by the earlier ones' boxes: its faces
//! stay out of the earlier block's bounding box even where the two meet on a
//! staircase of planes, which no single separating plane (the slab bound
//! overlap_volume_bound()) settles.
//!
//! In a frame F (a rotation): X = the bounding box of F a (coordinates
//! rounded, X widened by the rounding bound, so X contains the exact F a);
//! Y = X shrunk by a margin m (1e-13 x the largest coordinate: the
//! rounding noise of blocks that met on one plane in the canonical frame).
//! If no face of the rounded F b meets the open box Y (exact,
//! SolidIndex::any_face_meets_open_box) and Y's centre is outside it (exact
//! inside test), then no face of the exact F b meets Y shrunk by b's
//! rounding bound e, and that box Y' is outside b, so
//!     vol(a ∩ b) <= vol(X \ Y') / det F.
//! In the input frame (F = I) nothing is rounded: the bound is exactly 0.
#pragma once

#include <limits>
#include <memory>

#include <Eigen/Core>

#include "geometry/solid_index.h"
#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! A block seen in a frame: its vertices rotated (rounded), their rounding
//! bound, its bounding box there and an exact index of its faces.
class FramedBlock {
 public:
  //! `frame` must be a rotation (rows orthonormal within 1e-9); the block a
  //! closed solid.
  FramedBlock(const Mesh& block, const Eigen::Matrix3d& frame);
  const Eigen::Matrix3d& frame() const { return frame_; }
  const Box3& box() const { return box_; }            // bounding box of the rotated (rounded) vertices
  double rounding() const { return rounding_; }       // bound of |rounded - exact| per coordinate
  double largest() const { return largest_; }         // largest |rotated coordinate|
  const SolidIndex& index() const { return *index_; }

 private:
  Eigen::Matrix3d frame_;
  Box3 box_;
  double rounding_ = 0.0, largest_ = 0.0;
  std::unique_ptr<SolidIndex> index_;
};

//! Upper bound of vol(a ∩ b) (input units^3) when b stays out of a's
//! bounding box in their common frame (see the file comment); +infinity
//! when b's faces enter it, b contains it, or the frames differ.
double box_separation_bound(const FramedBlock& a, const FramedBlock& b);

}  // namespace subfab::detail
