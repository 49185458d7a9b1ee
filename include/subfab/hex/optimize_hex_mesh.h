// SPDX-License-Identifier: GPL-3.0-or-later
//! \file optimize_hex_mesh.h
//! Projection and finalisation of the hexahedral mesh (thesis D.6): the
//! boundary vertices are kept on the input surface while the vertices are
//! relaxed and the elements untangled, maximising the minimum scaled
//! Jacobian. The thesis used the edge-cone rectification of Livesu et al.
//! 2015 (no public code); this is a simpler, deterministic scheme, in passes:
//!   1. guarded projection: each boundary vertex not yet on the surface moves
//!      to its target (`targets`, else its closest point) the whole way, half
//!      or a quarter of it, whichever first keeps the worst scaled Jacobian of
//!      its hexahedra >= min(projection_floor, its value before);
//!   2. smart smoothing: Gauss-Seidel in vertex order, each vertex moving to
//!      the mean of its neighbours (boundary ones along the boundary, back
//!      onto the surface) only if the worst scaled Jacobian of its hexahedra
//!      does not drop;
//!   3. untangling: every vertex of a hexahedron whose scaled Jacobian is
//!      under target_quality takes a few gradient steps (central differences,
//!      backtracking) on a soft-min energy of the corners of its hexahedra,
//!      sum exp(-10 x corner scaled Jacobian); a boundary vertex on the
//!      surface moves in its tangent plane and is put back on the surface; no
//!      vertex goes farther than its initial mean edge from where it began.
//! The passes stop when every element reaches target_quality and every
//! boundary vertex is on the surface, when neither improves for 10 passes,
//! or after `passes`. Then, for elements still under 0.02, a last resort lets
//! their boundary vertices leave the surface (by at most a quarter edge) and
//! raises the worst element by a pattern search; kept only if it helped.
//! Gauss-Seidel sweeps in vertex order, run in parallel waves that give the
//! serial sweep's result bit for bit (src/hex/gauss_seidel_schedule.h):
//! deterministic whatever the number of threads.
#pragma once

#include <cstddef>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/hex/hex_mesh.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

struct OptimizeHexMeshOptions {
  int relax_iterations = 0;     // plain Laplacian passes before the others (they can fold curved tubes, off by default)
  int passes = 100;             // at most this many smart smoothing + untangling passes (steps 2 and 3)
  double target_quality = 0.5;  // hexahedra under this scaled Jacobian get their vertices optimised
  bool smooth = true;           // run the smart smoothing of step 2 (else untangling only)
  const std::vector<Vec3>* targets = nullptr;  // per vertex: where a boundary vertex goes (null: closest point)
  bool guard_projection = true;    // move boundary vertices to their targets only in steps that keep validity
  double projection_floor = 0.1;   // a projection step may lower its hexahedra's worst scaled Jacobian to this
  Progress* progress = nullptr;
};

struct OptimizeHexMeshReport {
  double min_before = 0;  // worst scaled Jacobian after relaxation (step 1)
  double min_after = 0;
  std::size_t num_inverted = 0;  // hexahedra with scaled Jacobian <= 0 at the end
  std::size_t num_off_surface = 0;  // boundary vertices left off the surface (could not reach it validly)
  int passes = 0;
};

//! Optimises `mesh` in place; its boundary vertices are moved onto `surface`.
OptimizeHexMeshReport optimize_hex_mesh(HexMesh& mesh, const Mesh& surface, const OptimizeHexMeshOptions& options = {});

}  // namespace subfab
