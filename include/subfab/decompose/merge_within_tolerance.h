// SPDX-License-Identifier: GPL-3.0-or-later
//! \file merge_within_tolerance.h
//! Fewer blocks within a tolerance (issue 17, point 2; the trade of thesis
//! Section 4.3.5, fewer blocks for a measured loss of faithfulness, made
//! with exact blocks): after the exact decomposition and its exact merges
//! (merge_blocks), two touching blocks A and B are replaced by the MILLED
//! SHAPE of A ∪ B along one of the six directions (milled_shape.h: what a
//! 3-axis machine makes of it, an exact height field) when
//!   - the milled shape is a closed 2-manifold within the height and machine
//!     limits,
//!   - the model then made, the input solid with every block that sticks out
//!     of it, stays within the tolerance T of the input: symmetric Hausdorff
//!     distance between the two surfaces <= T, measured near the new block by
//!     FillDeviationMeter (exact booleans, bounded-error distances: the
//!     measured value plus its error bound must be <= T, so the tolerance is
//!     honoured, never on average), and
//!   - it overlaps no other block (exact intersection volume <= 1e-6 x the
//!     smaller, as validate's overlap check). A ∪ B overlaps none, so only
//!     the fill the milled shape adds can: a block the fill's boxes do not
//!     reach, or whose interior misses them all (exact), is not checked
//!     further; the others exactly, both clipped near those boxes.
//! Every output block is therefore an exact height field (its milled shape
//! is itself), blocks do not overlap, and the union is within T.
//!
//! Outline: rounds until nothing changes: list the touching pairs not yet
//! rejected; evaluate them in parallel (the exact union; the directions in
//! order: the larger block's, the other's, the rest; the first that passes
//! wins); apply the accepted merges from the pair whose smaller block is
//! smallest, each block once per round, and none whose region meets a block
//! changed earlier in the round (it is evaluated again next round).
//! Deterministic whatever the thread count.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/decompose/carve_blocks.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of merge_within_tolerance().
struct ToleranceMergeOptions {
  double tolerance = 0.0;         // T, model units (> 0): the deviation allowed
  double error_fraction = 0.05;   // error bound of the distance measures, fraction of T (0, 1)
  double max_height = std::numeric_limits<double>::infinity();  // block extent along its axis, model units
  Vec3 machine_size = Vec3::Constant(std::numeric_limits<double>::infinity());  // X, Y, Z work volume, model units
  double collision_tolerance = 1e-6;  // overlap volume allowed, fraction of the smaller block (validate's)
  double screen_factor = 1.0;     // a direction is not tried when the material it would leave under a face is
                                  // thicker than this x T (measured below the face's centroid, normal to it;
                                  // a heuristic that saves time, never a validity test)
  std::size_t max_pair_faces = 12000;  // pairs with more faces in all are not tried (the exact union and the
                                  // milled shape of two large blocks take seconds each, and rarely pass)
  std::size_t max_region_faces = 20000;  // a merge whose deviation would be measured over more input faces is
                                  // not taken (the exact booleans of the measure grow with the region)
  int max_rounds = 64;            // rounds of pairwise merging
  const std::vector<char>* filled = nullptr;  // per input block: 1 when it already sticks out of the solid
                                  // (milled shapes of mill_within_tolerance()); nullptr: none does
  std::function<std::string(const Block&)> block_defect;  // the export's check of a merged block (decompose():
                                  // RoundedBlockCheck, rounded to the input frame); a merge whose block it
                                  // finds a defect in is not taken. Empty: not checked. Called in parallel
  const std::vector<char>* focus = nullptr;   // per input block: when set, only pairs holding a block flagged 1
                                  // are tried (remove_slivers(): each sliver with its neighbours); a merged
                                  // block is not flagged. nullptr: every touching pair
  bool clean_rounding = false;    // a union whose rounding to doubles leaves zero-area or flipped faces gets
                                  // export's cleanup (clean_rounded_block(), 1e-10 x scale, added to the
                                  // deviation bound) instead of being rejected (remove_slivers() sets it)
  Progress* progress = nullptr;   // progress and info (nullptr: silent)
};

//! Result of merge_within_tolerance().
struct ToleranceMergeResult {
  std::vector<Block> blocks;         // exact height fields, canonical frame
  std::vector<char> filled;          // per block: 1 when it sticks out of the solid (holds filled undercuts)
  std::size_t num_merges = 0;        // merges applied
  std::size_t num_candidates = 0;    // (pair, direction) milled shapes evaluated
  double max_deviation = 0.0;        // largest bound (measure + error) of an applied merge, model units
};

//! Merges touching blocks into their milled shapes while the model stays
//! within the tolerance (see the file comment).
//! \param solid  the solid the blocks were carved from (canonical frame)
//! \param blocks exact height-field blocks of `solid` (carve_blocks/merge_blocks)
ToleranceMergeResult merge_within_tolerance(const Mesh& solid, std::vector<Block> blocks,
                                            const ToleranceMergeOptions& options);

}  // namespace subfab
