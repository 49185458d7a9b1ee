// SPDX-License-Identifier: GPL-3.0-or-later
//! \file raise_worst_scaled_jacobian.h
//! Targeted pass on the worst hexahedra (thesis D.6, "untangling and quality
//! optimisation"; Table D.1 reports the minimum scaled Jacobian), run on the
//! finest level after raise_min_scaled_jacobian() and
//! pull_boundary_to_surface(), before raise_mean_scaled_jacobian().
//!
//! The passes before it move one vertex at a time (or, for a few elements,
//! minimise sum exp(-10 x corner), which still weighs the good corners): the
//! worst elements left are padding hexahedra whose worst corner is at a
//! boundary vertex where a boundary quad has a small angle (fertility: 26 to
//! 48 degrees), which only a joint move of the boundary vertices around it,
//! sliding on the surface, can open. Here:
//!   1. the hexahedra under `threshold` are the targets; worst first, a
//!      target none of whose vertices is in an earlier patch starts a patch:
//!      its vertices grown by `rings` rings of edge neighbours (not into an
//!      earlier patch); at most `max_patches` per round;
//!   2. all the vertices of a patch move together, by gradient ascent on the
//!      soft minimum -1/beta log sum exp(-beta alpha_c) over every corner c
//!      of the hexahedra they touch (analytic gradient, each vertex's step
//!      scaled by its squared mean edge and capped at `max_step` of it),
//!      beta = `sharpness`, then 2x and 4x when a step fails (continuation:
//!      the soft minimum tends to the true one); a boundary vertex on the
//!      surface takes the gradient's tangent part and is put back onto the
//!      surface (closest point), never farther than `max_slide` of its mean
//!      edge from where it started; a boundary vertex off the surface (left
//!      there by the passes before) moves freely but never farther from it;
//!   3. a step is kept only if the soft minimum rises and the smallest corner
//!      of those hexahedra does not drop: the mesh's minimum never drops,
//!      nothing inverts, and elements outside the patches do not change.
//! Up to `rounds` rounds (targets recomputed), stopping when a round does
//! not raise the mesh's minimum. Serial, in a fixed order: deterministic.
//! docs/hexmesh.md, "Worst elements".
#pragma once

#include <cstddef>

#include "subfab/hex/hex_mesh.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

struct RaiseWorstScaledJacobianOptions {
  double threshold = 0.5;   // hexahedra under this scaled Jacobian are the targets
  int rings = 3;            // a patch: the targets' vertices grown by this many rings of edge neighbours
  double sharpness = 40.0;  // beta of the soft minimum over the patch's corners (then 2x, 4x)
  int max_steps = 200;      // gradient steps per patch and round, at most
  double max_step = 0.2;    // largest step of a vertex, fraction of its mean edge
  double max_slide = 1.0;   // a boundary vertex slides at most this far from where it started, fraction of its mean edge
  double max_off_surface = 0;  // > 0: the boundary vertices of the targets may leave the surface by this fraction of their mean edge
  int restarts = 20;        // then again from the patch's inside relaxed by this many Jacobi iterations (0: no restart)
  std::size_t max_patches = 8;   // patches per round, at most (the worst targets first)
  int rounds = 3;           // rounds over the targets, at most
};

struct RaiseWorstScaledJacobianReport {
  double min_before = 0, min_after = 0;  // worst scaled Jacobian of the mesh (min_after >= min_before)
  double avg_before = 0, avg_after = 0;  // average scaled Jacobian
  std::size_t targets_before = 0, targets_after = 0;  // hexahedra under the threshold
  std::size_t patches = 0;               // patches optimised (over all rounds)
  std::size_t steps = 0;                 // accepted joint steps
  int rounds = 0;
};

//! Raises the worst scaled Jacobians of `mesh` in place; boundary vertices
//! slide on `surface`, the closed input solid.
RaiseWorstScaledJacobianReport raise_worst_scaled_jacobian(HexMesh& mesh, const Mesh& surface,
                                                           const RaiseWorstScaledJacobianOptions& options = {});

}  // namespace subfab
