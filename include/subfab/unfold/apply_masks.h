// SPDX-License-Identifier: GPL-3.0-or-later
//! \file apply_masks.h
//! Stage 4 of the unfoldable simplification (thesis Section 3.3.1
//! "Geometry" and Appendix A): sign flips on the lattice, guided by the mask
//! catalogue, that remove or move small marching-cubes configurations so the
//! surface has fewer, larger planar facets.
//!
//! Outline:
//!   queue <- every lattice point next to the surface, in index order
//!   while queue not empty and the flip cap is not reached:
//!     a <- pop front
//!     for every oriented mask matching the signs around a:
//!       for every POI set S of the mask (points not frozen, off the border,
//!       and next to the ORIGINAL surface: the surface -> input side of the
//!       fidelity band):
//!         flip S tentatively, one point at a time; reject S if a flip is
//!         not topology-preserving (simple point, (6,18) adjacency) or makes
//!         two cubes use the crossing diagonals of their shared face (the
//!         surface would touch itself there) or leaves a sample of the
//!         input with no sign change within `fidelity_radius` (the input ->
//!         surface side of the fidelity band, see fidelity_band.h);
//!         dE <- change of E over the cubes around S (E = number of
//!         triangle edges whose two triangles have different normals)
//!       eligible: dE < 0, or dE = 0 for a mask with several POI sets when
//!         the move grows the bigger adjacent chart
//!       among eligible sets take the one whose adjacent charts are biggest
//!         (area, flood fill inside the charts), then smallest dE
//!       flip it; push every point within 2 of it to the queue
//!     if no mask applies: flip `a` alone if that is simple, keeps the
//!       fidelity band and lowers E, or keeps E and grows the biggest
//!       adjacent chart (single_point_moves; our addition, not in the thesis)
//! The marching-cubes triangles of a cube are a function of its 8 signs, so
//! a flip changes only the 8 cubes around each flipped point: E, the charts
//! around them and the validity checks are all evaluated on those cubes and
//! their neighbours. Termination: every point may flip at most
//! max_flips_per_point times (a point flipped back and forth is a loop: it is
//! frozen and counted), and the total is capped.
#pragma once

#include <cstddef>

#include "subfab/core/progress.h"
#include "subfab/mesh/mesh.h"
#include "subfab/unfold/build_lattice.h"
#include "subfab/unfold/extract_charts.h"
#include "subfab/unfold/marching_cubes.h"

namespace subfab {

//! Options of apply_masks().
struct MaskOptions {
  int max_flips_per_point = 2;      // a point may change sign at most this often (loop guard)
  std::size_t max_total_flips = 0;  // global cap on flips; 0 = 4 x the number of surface points
  int chart_probe_triangles = 128;  // flood-fill cap (triangles) when measuring a chart's area
  bool single_point_moves = true;   // after the catalogue, also flip a lone surface point when
                                    // that strictly lowers the local energy (not in the thesis)
  bool neutral_single_point_moves = true;  // single-point moves also when the energy stays the same
                                           // and the biggest adjacent chart grows (not in the thesis)
  //! The input surface (model units, same frame as the lattice); when given,
  //! no move may leave a point of it farther than fidelity_radius from the
  //! surface (fidelity band). Null: only the point band applies.
  const Mesh* reference = nullptr;
  double fidelity_radius = 1.5;     // grid spacings (> 0): ball around each input sample that must
                                    // keep a lattice edge with a sign change (a surface vertex)
  Progress* progress = nullptr;     // optional progress receiver
};

//! Result of apply_masks().
struct MaskResult {
  Lattice lattice;                      // the lattice after the flips
  McSurface surface;                    // its marching-cubes surface
  Charts charts;                        // its facets ("facets_after_masks" = charts.poly.num_facets())
  std::size_t num_flips = 0;            // point flips applied
  std::size_t num_moves = 0;            // POI sets applied
  std::size_t num_rejected_topology = 0;  // POI sets refused: topology change or self-contact
  std::size_t num_rejected_fidelity = 0;  // moves refused: they would leave the fidelity band
  std::size_t num_fidelity_constraints = 0;  // distinct sample balls of the fidelity band
  std::size_t num_frozen_points = 0;    // points that reached max_flips_per_point (loops cut)
  bool hit_flip_cap = false;            // stopped by max_total_flips
};

//! Applies the masks of Appendix A to `lattice` until no mask improves the
//! surface (see the file comment). The surface stays closed, 2-manifold and
//! of the same topology (only simple points are flipped; the lattice border
//! never changes). Deterministic (one fixed processing order).
//! Fidelity: every flipped point is next to the original surface, so every
//! vertex of the result is within 1.5 spacings of the input; with
//! options.reference, every sample of the input keeps a surface vertex
//! within options.fidelity_radius spacings (if the original lattice had one).
//! \param lattice a lattice from build_lattice() (outer layer outside).
//! \throw InvalidArgumentError if fidelity_radius is not > 0.
MaskResult apply_masks(const Lattice& lattice, const MaskOptions& options = {});

}  // namespace subfab
