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
//!   1. the vertex's part of E (its hexahedra) and its analytic gradient; a
//!      boundary vertex on the surface takes the gradient's tangent part and
//!      every trial point is put back onto the surface (closest point): it
//!      slides on the input, within `max_slide` of its mean edge of where it
//!      started; a boundary vertex already off the surface (left there by
//!      raise_min_scaled_jacobian's last resort or loose vertices) moves
//!      freely but never farther from it;
//!   2. a line search (halving from twice the vertex's last step, then the
//!      minimum of the parabola through E(0), E'(0) and E(t)), at most
//!      `moves_per_visit` times; then the visit's displacement times
//!      `over_relaxation` (nonlinear SOR: Gauss-Seidel alone is slow on the
//!      smooth part of the error) if that is valid and still lowers E;
//!   3. a move is accepted only if every hexahedron h of the vertex keeps
//!      scaled Jacobian >= min(its value before the move, floor), floor =
//!      max(`floor`, the mesh's minimum at the start): the minimum of the
//!      mesh never drops and nothing becomes inverted. The floor is the
//!      held-vertex stage's (pull_boundary_to_surface, `patch_floor` = 0.3):
//!      that stage leaves its patches between the mesh's minimum and 0.5, at
//!      the max-min optimum of their joint ascent, where no single vertex
//!      can raise one hexahedron without lowering a neighbour; with a floor
//!      of 0.5 each of them could only rise, and they stayed frozen (rocker
//!      arm: 139 hexahedra under 0.5 after that stage, 53 after this pass).
//! After the first sweep a vertex is visited only when a vertex of its
//! hexahedra moved by more than `active_move` of its mean edge in the last
//! sweep. Stops after five sweeps in a row that raise the best average scaled
//! Jacobian by less than `min_gain`, or after `max_sweeps`; the positions
//! with the best average are kept. Run in parallel waves with the result of
//! the serial sweep (src/hex/gauss_seidel_schedule.h): deterministic
//! whatever the number of threads. docs/hexmesh.md, "Average pass".
#pragma once

#include <cstddef>

#include "subfab/hex/hex_mesh.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

struct RaiseMeanScaledJacobianOptions {
  double sharpness = 20.0;   // beta of the per-hexahedron soft minimum of its 8 corner determinants (dimensionless)
  double floor = 0.3;        // a move may lower a hexahedron's scaled Jacobian, but not under this (nor under the
                             // mesh's minimum; a hexahedron already under it may only rise); 0.5 froze the
                             // patches the held-vertex stage leaves under 0.5 (rocker arm .901 instead of .906)
  int max_sweeps = 100;      // sweeps over every vertex, at most (25 and 2e-4 until session 32: rocker arm .906 with
                             // a slide of 0.1; 100 and 2e-5 with 0.25: .911, every model under 7.5 s idle)
  double min_gain = 2e-5;    // stop when five sweeps in a row raise the best average scaled Jacobian by less than this
  int moves_per_visit = 1;   // line searches per vertex visit (2 or 3: the same quality per unit of time)
  double over_relaxation = 1.8;  // the visit's displacement times this, if still valid and lower (1: plain Gauss-Seidel)
  double active_move = 1e-3;  // after the first sweep, a vertex is visited only if a vertex of its hexahedra moved
                              // by more than this fraction of its mean edge in the last sweep (0: every vertex)
  bool slide_boundary = true;  // boundary vertices slide on the surface (false: they stay where they are) ...
  double max_slide = 0.25;     // ... at most this far from where they were, fraction of their mean edge (0.1 until
                               // session 32: averages .004-.015 lower, face-sampled mean distance 0-4 % lower)
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
