// SPDX-License-Identifier: GPL-3.0-or-later
//! \file pull_boundary_to_surface.h
//! Last step of the hexahedral mesh (thesis D.6: the boundary of the mesh is
//! mapped onto the input surface): boundary vertices that the earlier passes
//! left off the surface are pulled back onto it where that costs (almost) no
//! quality. The guarded projection of optimize_hex_mesh() stops a vertex
//! short of its target when the whole move would invert or flatten an
//! element, and the final pass's loose boundary vertices leave the surface
//! by up to a quarter edge; once the interior has been optimised, many of
//! them can reach the surface.
//!
//! In sweeps over the boundary vertices in index order (Gauss-Seidel,
//! serial: deterministic), each vertex farther than `tolerance` x its mean
//! edge from the surface tries to move to its closest point on the surface,
//! then 1/2 and 1/4 of the way; the first try is kept whose worst scaled
//! Jacobian among the vertex's hexahedra is at least
//!     min(before, max(before - max_loss, mesh minimum before the pass)),
//! so the mesh's minimum never drops and no neighbourhood loses more than
//! `max_loss` of its worst element. Stops after `sweeps` sweeps or when a
//! sweep moves nothing.
#pragma once

#include <cstddef>

#include "subfab/hex/hex_mesh.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

struct PullBoundaryOptions {
  int sweeps = 4;            // at most this many sweeps over the boundary vertices
  double max_loss = 0.0;     // a move may lower the worst scaled Jacobian of the vertex's hexahedra by at most this
  double tolerance = 1e-6;   // vertices closer than this x their mean edge to the surface are left alone
};

struct PullBoundaryReport {
  std::size_t off_before = 0, off_after = 0;  // boundary vertices farther than the tolerance
  std::size_t moves = 0;                      // accepted moves (whole or part of the way)
  double max_off_before = 0, max_off_after = 0;  // largest distance of a boundary vertex to the surface (model units)
  int sweeps = 0;
};

//! Moves boundary vertices of `mesh` towards `surface` (the closed input
//! solid) as described above; the mesh's minimum scaled Jacobian never drops.
PullBoundaryReport pull_boundary_to_surface(HexMesh& mesh, const Mesh& surface, const PullBoundaryOptions& options = {});

}  // namespace subfab
