// SPDX-License-Identifier: GPL-3.0-or-later
//! \file raise_mean_scaled_jacobian.h
//! Average-quality pass of the hexahedral mesh (thesis D.6, "untangling and
//! quality optimisation"; Table D.1 reports the average scaled Jacobian),
//! run on the finest level after raise_min_scaled_jacobian(). That pass is
//! max-min: a move may never lower the smallest corner a vertex moves, and
//! its energy sees only the worst corner of each hexahedron, so the average
//! converges slowly. This one maximises a smooth surrogate of the average:
//!   E = sum over hexahedra h of softmin_beta(h)
//!     = sum_h -1/beta log sum_{corners c of h} exp(-beta alpha_c),
//! alpha_c the corner determinants of the normalised edges (the scaled
//! Jacobian of h is min_c alpha_c; softmin_beta tends to it as beta grows,
//! and is smooth, so a descent direction exists where the min has a kink).
//! Nonlinear Gauss-Seidel, in sweeps over every vertex (index order):
//!   1. the vertex's part of E (its hexahedra), its gradient by central
//!      differences; a boundary vertex on the surface takes the gradient's
//!      tangent part and every trial point is put back onto the surface
//!      (closest point): it slides on the input; a boundary vertex already off
//!      the surface (left there by the last resort or the loose vertices of
//!      raise_min_scaled_jacobian) moves freely but never farther from it;
//!   2. a line search (halving from a quarter of its mean edge, then the
//!      minimum of the parabola through the two values and the slope), at most
//!      `moves_per_visit` times;
//!   3. a move is accepted only if every hexahedron h of the vertex keeps
//!      scaled Jacobian >= min(its value before the move, floor), floor =
//!      max(`floor`, the mesh's minimum at the start): the minimum of the
//!      mesh never drops and nothing becomes inverted.
//! Stops when a sweep raises the average scaled Jacobian by less than
//! `min_gain`, or after `max_sweeps`. Run in parallel waves with the result
//! of the serial sweep (src/hex/gauss_seidel_schedule.h): deterministic
//! whatever the number of threads.
#pragma once

#include <cstddef>

#include "subfab/hex/hex_mesh.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

struct RaiseMeanScaledJacobianOptions {
  double sharpness = 20.0;   // beta of the per-hexahedron soft minimum of its 8 corner determinants (dimensionless)
  double floor = 0.5;        // a move may lower a hexahedron's scaled Jacobian, but not under this (nor under the
                             // mesh's minimum; a hexahedron already under it may only rise)
  int max_sweeps = 20;       // sweeps over every vertex, at most
  double min_gain = 2e-4;    // stop when a sweep raises the average scaled Jacobian by less than this
  int moves_per_visit = 2;   // line searches per vertex visit
  double over_relaxation = 1.8;  // the visit's displacement times this, if still valid and lower (1: plain Gauss-Seidel)
  bool slide_boundary = true;  // boundary vertices slide on the surface (false: they stay where they are) ...
  double max_slide = 0.1;      // ... at most this far from where they were, fraction of their mean edge
};

struct RaiseMeanScaledJacobianReport {
  double avg_before = 0, avg_after = 0;  // average scaled Jacobian of the mesh
  double min_before = 0, min_after = 0;  // worst scaled Jacobian of the mesh (min_after >= min_before)
  std::size_t num_moves = 0;             // accepted line-search steps
  int sweeps = 0;
};

//! Raises the average scaled Jacobian of `mesh` in place without lowering its
//! minimum; boundary vertices on `surface` (the closed input solid) slide on
//! it. Hexahedron count and connectivity are unchanged.
RaiseMeanScaledJacobianReport raise_mean_scaled_jacobian(HexMesh& mesh, const Mesh& surface,
                                                         const RaiseMeanScaledJacobianOptions& options = {});

}  // namespace subfab
