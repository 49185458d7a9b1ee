// SPDX-License-Identifier: GPL-3.0-or-later
//! \file clean_skeleton.h
//! Automatic clean-up of a curve-skeleton, the step the thesis did by hand
//! with Skeleton Lab (Appendix D.7: "we manually simplified the skeleton,
//! merging nearby branching nodes"). Repeated until nothing changes:
//!   1. collapse: two branching nodes (degree >= 3) joined by an arc whose
//!      maximal spheres overlap (|p_a - p_b| < r_a + r_b) become one node
//!      (the arc's nodes merge into it; it takes the larger radius and the
//!      radius-weighted mean position); never when that would close a cycle
//!      of fewer than three nodes (loops, hence genus, are kept);
//!   2. prune: a terminal arc (from a degree-1 node to a branching node)
//!      shorter than prune_factor x the branching node's radius is removed;
//!   3. drop redundant degree-2 nodes: a node closer than
//!      collinear_tolerance x its radius to the segment joining its two
//!      neighbours is removed and its neighbours joined.
//! Nodes are renumbered in their original order (deterministic).
#pragma once

#include <cstddef>

#include "subfab/hex/skeleton.h"

namespace subfab {

struct CleanSkeletonOptions {
  double prune_factor = 1.0;           // prune terminal arcs shorter than this x the branch node's radius
  double collinear_tolerance = 0.02;   // drop a degree-2 node this close to its neighbours' segment (x radius)
};

struct CleanSkeletonReport {
  std::size_t branches_collapsed = 0;  // arcs between branching nodes collapsed
  std::size_t branches_pruned = 0;     // terminal arcs removed
  std::size_t nodes_dropped = 0;       // redundant degree-2 nodes removed
};

//! The cleaned skeleton. \pre check_skeleton(skeleton) passes.
Skeleton clean_skeleton(const Skeleton& skeleton, const CleanSkeletonOptions& options = {},
                        CleanSkeletonReport* report = nullptr);

}  // namespace subfab
