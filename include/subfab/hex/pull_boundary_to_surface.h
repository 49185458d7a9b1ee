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
//!
//! Second stage (`rings` > 0; issue 14, thesis D.6 keeps every boundary
//! vertex on the surface): most vertices left are held because their
//! padding hexahedron would flatten if the vertex moved alone (on the seven
//! bench models, 11 to 312 of them, up to two mean edges off the surface).
//! In `snap_sweeps` sweeps in index order, each such vertex (or cluster of
//! up to `max_cluster` held vertices connected along boundary edges) moves
//! to its closest point on the surface in `patch_stages` equal steps; its
//! inner neighbours (the other ends of its padding edges) are carried by the
//! same step, so no padding edge turns over (a gradient step cannot undo
//! that: the normalised corner jumps through 0); after each step the patch
//! (the vertex and `rings` rings of edge neighbours; the vertex fixed, its
//! boundary neighbours sliding on the surface, the inner ones free) takes up
//! to `patch_steps` steps of raise_worst_scaled_jacobian()'s joint ascent
//! on the soft minimum of its corners, when its worst hexahedron is under
//!     need = min(its worst before, max(patch_floor, mesh minimum before)).
//! At the last step the vertex slides with its patch. The last step whose
//! patch is >= need is kept (all the way: `snapped`; part of it: `closer`);
//! none: the patch is back where it was. So the mesh's minimum never drops.
//! Serial, fixed order: deterministic.
#pragma once

#include <cstddef>

#include "subfab/hex/hex_mesh.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

struct PullBoundaryOptions {
  int sweeps = 4;            // at most this many sweeps over the boundary vertices
  double max_loss = 0.0;     // a move may lower the worst scaled Jacobian of the vertex's hexahedra by at most this
  double tolerance = 1e-6;   // vertices closer than this x their mean edge to the surface are left alone
  // then each vertex still off the surface is put on it with its neighbourhood re-optimised:
  int snap_sweeps = 1;       // sweeps over the vertices still off the surface, at most
  std::size_t max_cluster = 1;  // held vertices connected along boundary edges move together, at most this many
  int patch_stages = 4;      // moved to the surface in this many steps, the patch re-optimised after each
  int rings = 2;             // the patch: the vertex and this many rings of edge neighbours (0: no second stage)
  double patch_floor = 0.3;  // accepted when the patch's worst hexahedron is >= min(its value before, max(this, mesh minimum))
  int patch_steps = 40;      // joint gradient steps on the patch (raise_worst_scaled_jacobian's ascent), at most
  int patch_restarts = 0;    // > 0: again from the patch's inside relaxed by this many Jacobi iterations
  double patch_slide = 1.0;  // the patch's boundary vertices slide at most this far, fraction of their mean edge
};

struct PullBoundaryReport {
  std::size_t off_before = 0, off_after = 0;  // boundary vertices farther than the tolerance
  std::size_t moves = 0;                      // accepted moves (whole or part of the way)
  double max_off_before = 0, max_off_after = 0;  // largest distance of a boundary vertex to the surface (model units)
  int sweeps = 0;
  std::size_t held = 0;        // vertices still off the surface after the sweeps (second stage)
  std::size_t snapped = 0;     // of those, put on the surface with their patch re-optimised
  std::size_t closer = 0;      // of those, moved part of the way only
  int snap_sweeps = 0;
  std::size_t snap_steps = 0;  // joint steps taken by the accepted patches
};

//! Moves boundary vertices of `mesh` towards `surface` (the closed input
//! solid) as described above; the mesh's minimum scaled Jacobian never drops.
PullBoundaryReport pull_boundary_to_surface(HexMesh& mesh, const Mesh& surface, const PullBoundaryOptions& options = {});

}  // namespace subfab
