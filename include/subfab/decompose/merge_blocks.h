// SPDX-License-Identifier: GPL-3.0-or-later
//! \file merge_blocks.h
//! Post-processing of the carved blocks (thesis Section 4.3.4, "Post
//! Processing"): two blocks with the same milling direction that touch are
//! replaced by their union when the union is still a valid block: one
//! connected closed 2-manifold, an exact height field along the direction
//! (every face facing away from it lies on the base plane), within the
//! height and machine limits. The union is computed and checked exactly
//! (CGAL corefinement on an exact kernel), then checked again after rounding
//! to doubles. This covers the thesis's "raise the base of the lower block"
//! case (a block standing on another whose top it exactly covers) and side
//! by side blocks on a common base.
//!
//! Outline: repeat until nothing changes: evaluate every touching pair of
//! same-direction blocks (in parallel), then apply the valid merges in
//! (i, j) order, each block merged at most once per round.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/decompose/carve_blocks.h"

namespace subfab {

//! Options of merge_blocks().
struct MergeOptions {
  double max_height = std::numeric_limits<double>::infinity();  // block extent along its axis, model units
  Vec3 machine_size = Vec3::Constant(std::numeric_limits<double>::infinity());  // X, Y, Z work volume, model
      // units: extent along the axis <= Z, the two others fit X x Y in either order
  int max_rounds = 16;           // rounds of pairwise merging
  Progress* progress = nullptr;  // progress and info (nullptr: silent)
};

//! Result of merge_blocks().
struct MergeResult {
  std::vector<Block> blocks;   // the blocks after merging, in the order of their first part
  std::size_t num_merges = 0;  // unions performed
  std::size_t num_candidates = 0;  // pairs evaluated
};

//! Merges adjacent same-direction blocks whose union is a valid block
//! (thesis Section 4.3.4). Deterministic whatever the thread count.
//! \param blocks closed, outward-oriented blocks in the canonical frame
MergeResult merge_blocks(std::vector<Block> blocks, const MergeOptions& options = {});

}  // namespace subfab
