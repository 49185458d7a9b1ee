// SPDX-License-Identifier: GPL-3.0-or-later
//! \file merge_blocks.h
//! Post-processing of the carved blocks (thesis Section 4.3.4, "Post
//! Processing"): two blocks that touch are replaced by their union when the
//! union is still a valid block: one connected closed 2-manifold, an exact
//! height field along one of the six directions (every face facing away
//! from it lies on the base plane), within the height and machine limits.
//! The union is computed and checked exactly (CGAL corefinement on an exact
//! kernel), then checked again after rounding to doubles. This covers the
//! thesis's "raise the base of the lower block" case (a block standing on
//! another whose top it exactly covers), side by side blocks on a common
//! base, and (beyond the thesis, which merges same-direction blocks only)
//! blocks of different directions whose union one direction can mill, such
//! as the thin slivers that cycle splits and trims leave at the surface.
//!
//! Outline: repeat until nothing changes: evaluate every touching pair of
//! blocks (in parallel): the directions are tried in order, the larger
//! block's, the other's, then the rest, each skipped when a cheap test on
//! the faces facing away from it rules it out, and the exact union takes the
//! first it is a height field along; then apply the valid merges in (i, j)
//! order, each block merged at most once per round.
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
  double max_overhang_deg = 0.0;  // faces may lean this far past vertical and count as facing the axis (degrees,
                                  // [0, 45], see overhang_sine(); 0 = exact height fields)

  bool any_direction = true;     // the union may take any of the six directions (false: only pairs of
                                 // the same direction, which the union keeps; the thesis's merge)
  Progress* progress = nullptr;  // progress and info (nullptr: silent)
};

//! Result of merge_blocks().
struct MergeResult {
  std::vector<Block> blocks;   // the blocks after merging, in the order of their first part
  std::size_t num_merges = 0;  // unions performed
  std::size_t num_candidates = 0;  // pairs whose union was computed exactly
  std::vector<std::vector<std::size_t>> parts;  // per output block: the indices of the input blocks it unites, ascending
};

//! Merges adjacent blocks whose union is a valid block along the direction
//! of one of them (thesis Section 4.3.4). Deterministic whatever the thread
//! count.
//! \param blocks closed, outward-oriented blocks in the canonical frame
MergeResult merge_blocks(std::vector<Block> blocks, const MergeOptions& options = {});

}  // namespace subfab
