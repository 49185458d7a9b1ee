// SPDX-License-Identifier: GPL-3.0-or-later
//! \file mill_within_tolerance.h
//! The blocks carved under tolerance allowances (tolerance_allowances.h)
//! lean past vertical where the allowances let them; a 3-axis machine makes
//! their MILLED SHAPES (milled_shape.h). This stage replaces every block by
//! its milled shape and measures, exactly where it matters, whether the
//! result honours the tolerance T (issue 17, point 2; the trade of thesis
//! Section 4.3.5):
//!   1. the milled shape is a closed 2-manifold and an exact height field
//!      (a block that already is one stays as it is: it does not "stick
//!      out" of the input);
//!   2. it overlaps no other block (a bound from the boxes, then the exact
//!      intersection volume <= collision_tolerance x the smaller, as
//!      validate's overlap check); the carved blocks do not overlap, so only
//!      the pairs where a block's fill (the boxes fill_columns() gives) meets
//!      the other's box are checked, a pair whose interiors each miss the
//!      other's fill boxes is proven apart without a boolean (exact
//!      face/box and inside tests), and the exact check of the others runs
//!      on both shapes clipped near those boxes;
//!   3. the model then made, the input with every block that sticks out,
//!      stays within T of the input near it: FillDeviationMeter (exact
//!      booleans, bounded-error Hausdorff distances both ways), measured
//!      value + error bound <= T. Only where the milled shape adds material
//!      to the carved block can it deviate: the measure runs in the boxes
//!      fill_columns() gives (one parallel task per box), near the whole
//!      block only when those cannot be computed. Before it, a sampled lower
//!      bound fails a block for sure (fill_deviation_lower_bound.h) and an
//!      upper bound over the block's part outside the input keeps it for
//!      sure (fill_deviation_upper_bound.h: one exact difference, of the
//!      block clipped near its fill boxes, distances within the same error;
//!      not for a lone filled block, whose difference would run on one
//!      core); only the blocks neither decides are measured.
//! A block that fails any of them is reported; the caller takes the
//! allowances back there and decomposes again (decompose()).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/decompose/carve_blocks.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! What mill_within_tolerance() made of each block, kept for the next call
//! on the same solid: the rounds within a tolerance carve many blocks again
//! unchanged (max planck at 3.3e-3: 25 of the 132 blocks its rounds mill,
//! a fifth of their faces), and a block's milled shape, its fill boxes and
//! its part outside the solid depend on that block and the solid alone. A
//! block comes again when its mesh (vertices and faces, byte for byte) and
//! axis are the same; its results are then copied, not made again (the
//! same values: the output does not depend on the cache). Bound to the
//! first solid it is used with; a call on another solid empties it. Not for
//! concurrent calls.
class MillCache {
 public:
  MillCache();
  ~MillCache();
  MillCache(const MillCache&) = delete;
  MillCache& operator=(const MillCache&) = delete;
  std::size_t size() const;  // blocks held
  std::size_t hits() const;  // blocks found in it, over all calls
  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

//! Options of mill_within_tolerance().
struct MillToleranceOptions {
  double tolerance = 0.0;            // T, model units (> 0)
  double error_fraction = 0.05;      // error bound of the distance measures, fraction of T, in (0, 1)
  double collision_tolerance = 1e-6; // overlap volume allowed, fraction of the smaller block (validate's)
  std::size_t max_region_faces = 0;  // > 0: a block whose deviation measure would span more input faces fails
                                     // ("region too large"); 0 = no cap
  const std::vector<char>* measure = nullptr;  // per block: 0 = its deviation is known (known_deviation) and
                                     // nothing within its measure's reach changed since: not measured again (its
                                     // milled shape is still made and checked for collisions); nullptr = all measured
  const std::vector<double>* known_deviation = nullptr;  // per block, read where `measure` is 0 (model units)
  bool stop_at_first_failure = false;  // true: when the sampled lower bound (fill_deviation_lower_bounds())
                                     // already fails a block, the exact measure is not run: every filled block not
                                     // failed yet fails as "not measured" (MillToleranceResult::stopped); for a
                                     // candidate that any failure rejects (decompose()'s overhang ladder)
  bool locate_failures = false;      // true: the sampled lower bound goes on past the first point beyond T and
                                     // records every such point (MillToleranceResult::far_points; its cost: every
                                     // sample of a failing block, as for a passing one); decompose()'s rounds lower
                                     // the allowances there only
  MillCache* cache = nullptr;        // blocks milled before on the same solid, reused (nullptr: none kept)
  Progress* progress = nullptr;      // updates per block and info (nullptr: silent)
};

//! Result of mill_within_tolerance().
struct MillToleranceResult {
  std::vector<Block> blocks;          // per input block: its milled shape (an exact height field), or the block
  std::vector<char> filled;           // per block: 1 when the milled shape adds material (sticks out of the solid)
  std::vector<std::string> failures;  // per block: why it fails the tolerance (empty: it passes)
  std::vector<double> deviation;      // per block: the measured bound (measure + error), model units; 0 when exact
  double max_deviation = 0.0;         // over the blocks that pass, model units
  bool stopped = false;               // stop_at_first_failure stopped before the exact measure
  std::size_t num_bounded = 0;        // filled blocks kept within the tolerance by the bound over their parts
                                      // outside the solid (fill_deviation_upper_bound.h): not measured in
                                      // regions, their deviation is that bound
  std::vector<std::vector<Vec3>> far_points;  // per block, with locate_failures: the sampled points of the model
                                      // made (or of the input under a fill) farther than T from the other surface,
                                      // where its fill makes the model deviate; empty when the block passes or fails
                                      // for another reason (collision, not a height field, the exact measure)
  std::vector<char> collided;         // per block: 1 when its milled shape and another block's overlap (the pair's
                                      // filled blocks fail; the other, exact or not, may pass)
  std::size_t num_failed() const;
};

//! Milled shapes of the carved blocks, measured against the tolerance (see
//! the file comment). Parallel over blocks and pairs; deterministic.
//! \param solid  the solid the blocks were carved from (canonical frame)
//! \param blocks the carved blocks (carve_blocks() under allowances): closed
//!        solids whose interiors are pairwise disjoint
MillToleranceResult mill_within_tolerance(const Mesh& solid, std::vector<Block> blocks,
                                          const MillToleranceOptions& options);

}  // namespace subfab
