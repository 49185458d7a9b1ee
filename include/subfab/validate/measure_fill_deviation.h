// SPDX-License-Identifier: GPL-3.0-or-later
//! \file measure_fill_deviation.h
//! How far material added outside a solid moves its surface (issue 17,
//! point 2: the deviation of a decomposition within a tolerance; thesis
//! Section 4.3.5 measures faithfulness the same way, as a Hausdorff
//! distance to the input surface).
//!
//! A decomposition within a tolerance T replaces blocks by their milled
//! shapes (milled_shape.h), which stick out of the input solid S where they
//! fill undercuts. The model then made is S' = S ∪ F_1 ∪ ... ∪ F_n, the F_k
//! the blocks that stick out ("filled" blocks), and the deviation is the
//! symmetric Hausdorff distance between the surfaces ∂S' and ∂S (the cut
//! faces between blocks and the empty interior do not count: they are not
//! on either surface).
//!
//! FillDeviationMeter::measure() computes that distance near one filled
//! block F (the others near it included), exactly where it matters:
//!   1. Q = the input faces whose bounding box meets box(F) widened by the
//!      reach r; R' = the box around box(F) and Q, widened by r (and a hair);
//!   2. V = (F ∪ the other filled blocks, clipped to R') ∪ (S ∩ R'), by exact
//!      booleans (CGAL corefinement, exact kernel, deterministic arena);
//!      the faces of V on the planes of R' are cut faces of the clip, the
//!      others are ∂S' ∩ R' exactly;
//!   3. to_input = one-sided Hausdorff distance from those faces to ∂S;
//!      from_input = from Q to those faces (CGAL bounded error).
//! Why local is enough: a point of ∂S' outside box(F) was a point of the
//! surface before F was added, and a point of ∂S farther than r from box(F)
//! keeps a nearest point of ∂S' within r that F does not touch; so with r >=
//! the tolerance, adding F keeps the whole model within the tolerance iff
//! the local distances are within it; and with r >= the tolerance, every
//! nearest point within r of a point of Q lies inside R', where V's surface
//! is ∂S' exactly.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of FillDeviationMeter::measure().
struct FillDeviationOptions {
  double reach = 0.0;  // model units, >= 0: the input surface within this of the block's box is checked
                       // (set it to the tolerance, see the file comment)
  double error = 0.0;  // error bound of the Hausdorff distances, model units (> 0)
  std::size_t max_faces = 0;  // > 0: give up (failure "region too large") when more input faces than this lie in
                              // the region, before any boolean (the exact booleans grow with it); 0 = no cap
};

//! Result of FillDeviationMeter::measure() (model units).
struct FillDeviation {
  double to_input = 0.0;    // one-sided Hausdorff distance from ∂S' near the block to ∂S: how far the added
                            // material sticks out of the input
  double from_input = 0.0;  // one-sided Hausdorff distance from ∂S near the block to ∂S': how deep the input
                            // surface lies under added material
  double error = 0.0;       // error bound of both (the true values are within it)
  std::string failure;      // non-empty when an exact boolean failed: nothing was measured
  //! Upper bound of the symmetric distance (both plus the error bound).
  double bound() const { return std::max(to_input, from_input) + error; }
};

//! Measures the deviation that blocks sticking out of a solid cause, near
//! one of them (see the file comment). Thread-safe: measure() may run
//! concurrently; its result does not depend on the thread that runs it.
class FillDeviationMeter {
 public:
  //! \param solid closed, outward-oriented, self-intersection-free mesh (copied)
  explicit FillDeviationMeter(const Mesh& solid);
  ~FillDeviationMeter();
  FillDeviationMeter(const FillDeviationMeter&) = delete;
  FillDeviationMeter& operator=(const FillDeviationMeter&) = delete;

  //! The deviation of ∂(S ∪ block ∪ others) from ∂S near `block`.
  //! \param block  closed, outward-oriented 2-manifold (a milled shape), same frame as the solid
  //! \param others the other blocks that stick out of the solid (any number: those whose box
  //!               does not meet the region are skipped); none may overlap `block` in volume
  FillDeviation measure(const Mesh& block, const std::vector<const Mesh*>& others,
                        const FillDeviationOptions& options) const;

  const Mesh& solid() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace subfab
