// SPDX-License-Identifier: GPL-3.0-or-later
//! \file raise_min_scaled_jacobian.h
//! Last quality pass of the hexahedral mesh (thesis D.6, "untangling and
//! quality optimisation"), run on the finest level after optimize_hex_mesh():
//! a local optimisation of the worst elements. In sweeps:
//!   1. the vertices of every hexahedron whose scaled Jacobian is under
//!      `threshold` are visited, the worst first (ties: vertex index);
//!   2. each takes line searches along the descent direction (central
//!      differences) of the energy of its hexahedra,
//!      sum exp(-8 (q - q_min)) - q, q their scaled Jacobians: dominated by the
//!      worst, but a step may not buy a little on the worst element with a lot
//!      on the good ones (the average counts too); a step is taken only if it
//!      lowers that energy and does not lower the smallest corner determinant
//!      the vertex affects (its own and its edge neighbours' corners in each
//!      incident hexahedron); where that stalls under 0.15, a pattern search
//!      (axes and cube diagonals) raises that smallest corner directly. So the
//!      worst element of a neighbourhood never gets worse and no element
//!      becomes inverted;
//!   3. a boundary vertex moves in the surface's tangent plane and is put back
//!      onto it (closest point): it slides on the input.
//! Last resort, with `free_boundary_for_inverted`, when elements are still
//! inverted: the vertices of the hexahedra under 0.02 and their edge
//! neighbours move together (gradient steps on sum exp(-10 x corner) over the
//! corners they affect, backtracking): a vertex-by-vertex search stalls where
//! two vertices must move at once (the boundary folded over a thin rim, spot's
//! ear, the rocker arm's neck); the boundary vertices of those hexahedra may
//! leave the surface by `max_off_surface` of their mean edge, their
//! neighbours slide on it; then sweeps as above, boundary free within the same
//! bounds. Kept only if the worst element rose (validity first: the distance
//! to the input grows a little there; the report counts those vertices).
//! Then, when at most `repair_max_hexes` hexahedra are under `repair_below`,
//! the same joint repair lifts them (fertility .209 -> .310, humanoid .250 ->
//! .452: one boundary vertex whose four hexahedra all have angles over 100
//! degrees at it, a fold of the boundary's quad layout); kept only if the
//! worst element rose.
//! Finally up to `quality_sweeps` sweeps as in 1-3 over the hexahedra under
//! `quality_threshold` (by default every hexahedron), until a sweep raises the
//! average by less than `quality_gain`: the same moves, which cannot lower any
//! neighbourhood's worst element, raise the average (cactus .785 -> .871).
//! In those sweeps the boundary vertices of the hexahedra under `loose_below`
//! are loose, the surface attraction of the thesis's edge-cone rectification
//! (D.6, weight alpha) instead of the hard constraint: they move freely within
//! `max_off_surface` of their mean edge of the surface, their energy plus
//! loose_attraction x (distance / mean edge)^2; where the surface curves more
//! than the boundary quads (a limb's tip), a corner on the surface opens only
//! off it (cactus min .466 -> .528, mean distance unchanged).
//! Gauss-Seidel in a fixed order, run in parallel waves with the serial
//! result (src/hex/gauss_seidel_schedule.h): deterministic whatever the number
//! of threads.
#pragma once

#include <cstddef>

#include "subfab/hex/hex_mesh.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

struct RaiseMinScaledJacobianOptions {
  double threshold = 0.3;        // hexahedra under this scaled Jacobian have their vertices moved
  int sweeps = 20;               // at most this many sweeps (stops earlier when a sweep gains < 1e-4 on the minimum)
  bool free_boundary_for_inverted = true;  // last resort for elements still inverted (see above)
  double max_off_surface = 0.25; // last resort: how far a boundary vertex may leave the surface, fraction of its mean edge
  double repair_below = 0.3;      // then, if at most repair_max_hexes hexahedra are under this, the last resort's joint
  std::size_t repair_max_hexes = 16;  // repair lifts them (bounded: its cost grows with the patch; 0: never)
  double quality_threshold = 1.0; // then: sweeps as above over the hexahedra under this (the average rises) ...
  int quality_sweeps = 12;        // ... at most this many (0: none) ...
  double quality_gain = 2e-4;     // ... stopping when one raises the average scaled Jacobian less than this (and not the minimum)
  double loose_below = 0.5;       // in those sweeps, the boundary vertices of the hexahedra under this are loose: ...
  double loose_attraction = 1.0;  // ... free within max_off_surface of their mean edge of the surface, energy plus
                                  // loose_attraction x (distance / mean edge)^2 (0: every boundary vertex slides on the surface)
};

struct RaiseMinScaledJacobianReport {
  double min_before = 0, min_after = 0;   // worst scaled Jacobian of the mesh
  std::size_t num_inverted_before = 0, num_inverted_after = 0;
  std::size_t num_moves = 0;              // accepted vertex moves
  std::size_t num_off_surface = 0;        // boundary vertices the last resort moved off the surface
  std::size_t repaired_worst = 0;         // hexahedra under repair_below given the joint repair (0: none)
  std::size_t num_loose_moved = 0;        // loose boundary vertices the quality sweeps moved (off the surface, most of them)
  int sweeps = 0;
  int untangle_steps = 0;                 // steps of the joint untangling (last resort)
};

//! Raises the worst scaled Jacobians of `mesh` in place; boundary vertices
//! stay on (or are kept near) `surface`, the closed input solid.
RaiseMinScaledJacobianReport raise_min_scaled_jacobian(HexMesh& mesh, const Mesh& surface,
                                                       const RaiseMinScaledJacobianOptions& options = {});

}  // namespace subfab
