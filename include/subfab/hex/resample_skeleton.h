// SPDX-License-Identifier: GPL-3.0-or-later
//! \file resample_skeleton.h
//! Skeleton resampling (thesis Appendix D.4): the density of the hexahedral
//! mesh along the skeleton follows the local thickness of the shape.
//!
//! Every arc (see skeleton_arcs()) is parameterised by arc length on [0, 1],
//! positions and radii interpolated linearly along its polyline. The interval
//! [a, b] is split at its midpoint m, recursively, while the maximal spheres
//! at the ends and at the midpoint do not overlap:
//!     |p_a - p_m| > r_a + r_m   or   |p_m - p_b| > r_m + r_b,
//! or (not in the thesis) while a node of the polyline strictly inside
//! (a, b) has a radius under neck_ratio x min(r_a, r_b): the samples would
//! step over a neck, and the tube, sized by the radii at the samples, would
//! be too fat there (rocker arm: a neck of radius 0.048 between samples of
//! 0.12 folded the boundary and left 2 inverted elements).
//! On a loop (a cycle, or an arc back to its own start node) it is also split
//! (not in the thesis) while a node of the polyline strictly inside (a, b) is
//! farther than bend_ratio x min(r_a, r_b) from the chord p_a p_b: a loop as
//! thick as its bend has overlapping spheres across its hole, so D.4 keeps
//! three samples, and the straight tubes between them cut across the hole
//! (rocker arm: the hex boundary ran through the hole, 0.095 of the diagonal
//! from the surface, max distance 0.17; with the criterion 0.13 and a minimum
//! scaled Jacobian of .32 instead of .15). On open arcs it split the wiggles
//! of the computed skeletons into short thick layers (cactus inverted, bob's
//! minimum .66 -> .16), so it is not applied there.
//! Every arc keeps at least one inner node (a closed cycle at least two), so
//! that each arc becomes at least one layer of hexahedra between its ends.
//! Branching and terminal nodes keep their position and radius.
#pragma once

#include <cstddef>

#include "subfab/hex/skeleton.h"

namespace subfab {

struct ResampleSkeletonOptions {
  double neck_ratio = 0.0;   // also split while a node strictly inside the interval has a radius under this x the smaller end radius (0: off)
  double bend_ratio = 0.25;  // on loops, also split while a node strictly inside the interval is farther than this x the smaller end radius from the chord (0: off)
  int max_depth = 16;  // recursion limit per arc (at most 2^16 samples; a guard, never reached on real data)
};

//! The resampled skeleton: the branching and terminal nodes of `skeleton`
//! first (in their order), then the new inner nodes arc by arc.
//! \pre check_skeleton(skeleton) passes.
Skeleton resample_skeleton(const Skeleton& skeleton, const ResampleSkeletonOptions& options = {});

}  // namespace subfab
