// SPDX-License-Identifier: GPL-3.0-or-later
//! \file plan_gluing_order.h
//! An order in which to glue the blocks of a decomposition together, each
//! block slid into place along one axis of the decomposition frame without
//! passing through a block already placed (not in the thesis, which stops at
//! the blocks; see docs/view.md).
//!
//! Outline:
//!   1. blocking relation: for each axis k, cast a grid of rays parallel to
//!      k through the model; on every ray, each block's material is a set of
//!      intervals (crossings paired in depth order). Block B blocks block A
//!      along +k when some ray has material of B beyond (in +k) material of
//!      A: A cannot translate to +infinity along +k while B is there
//!      (and B cannot along -k while A is there).
//!   2. disassembly, greedily: while blocks remain, remove one that some
//!      direction frees from all the others (smallest volume first, the
//!      block's own milling direction first, then +z, -z, +x, -x, +y, -y).
//!      Removing a block never blocks another, so the greedy removal finds a
//!      complete sequence whenever one exists (for single-block translations
//!      along the six axes).
//!   3. the gluing order is the removal order reversed: each block is slid in
//!      from the side it was removed to, past exactly the blocks that were
//!      still there when it was removed.
//! Blocks that no single axis translation frees (interlocked) are listed in
//! `stuck`; they have to be put together as a group, first.
//! The rays sample the model: contacts narrower than the ray spacing can be
//! missed (the spacing is reported).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of plan_gluing_order() and compute_blocking().
struct GluingOptions {
  //! input frame -> decomposition frame (decomposition.json's "rotation"); the six axes are this frame's
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  int resolution = 200;  // rays per side of the model's bounding box, across each axis (spacing = largest side / this)
  //! per block, its milling axis 0..5 (+x, -x, +y, -y, +z, -z) tried first; empty or -1 = none
  std::vector<int> preferred_axis;
  //! per block, its volume (ties in removal order: smaller first); empty = all equal
  std::vector<double> volumes;
};

//! blocked[d][a][b] == true: block b stands in the way of block a sliding
//! out along axis d (0..5: +x, -x, +y, -y, +z, -z of the decomposition frame).
struct BlockingRelation {
  std::size_t num_blocks = 0;
  double ray_spacing = 0;  // model units
  std::array<std::vector<bool>, 6> blocked;  // [d][a * num_blocks + b]
  bool operator()(int d, std::size_t a, std::size_t b) const { return blocked[d][a * num_blocks + b]; }
};

//! One step of the gluing order.
struct GluingStep {
  std::size_t block = 0;  // index into the blocks given
  int axis = -1;          // slid in from this side, moving towards the model: 0..5 (+x ... -z); -1 = first block, or stuck
};

//! The gluing order.
struct GluingPlan {
  std::vector<GluingStep> steps;   // in gluing order; covers every block once
  std::vector<std::size_t> stuck;  // blocks that no single translation frees (the first steps, axis -1); usually empty
  double ray_spacing = 0;          // model units
};

//! "+x", "-x", "+y", "-y", "+z", "-z" for 0..5 ("" otherwise).
std::string axis_label(int axis);

//! 0..5 for "+x" ... "-z" (also "x" for "+x"); -1 otherwise.
int axis_index(const std::string& label);

//! The blocking relation of closed, outward-oriented block meshes (input frame).
BlockingRelation compute_blocking(const std::vector<Mesh>& blocks, const GluingOptions& options = {});

//! A gluing order of the blocks (input frame meshes; see the outline above).
GluingPlan plan_gluing_order(const std::vector<Mesh>& blocks, const GluingOptions& options = {});

}  // namespace subfab
