// SPDX-License-Identifier: GPL-3.0-or-later
//! \file smooth_for_decomposition.h
//! Thesis Section 4.3.5 ("Faithfulness vs Complexity") and 4.4.4: trade a
//! small, measured deviation from the input for fewer height-field blocks by
//! low-pass filtering the model before the decomposition (Taubin 1995), with
//! the guarantee that the result is still a valid solid. The thesis's second
//! step (reintroducing the details into the blocks) is restore_details(), run
//! by decompose_smoothed().
//!
//! Outline of smooth_for_decomposition():
//!   1. the input must be a closed, manifold, outward-oriented,
//!      self-intersection-free solid (require_closed_solid, exact);
//!   2. every `check_every` passes: that many Taubin (lambda, mu) passes
//!      (taubin_smooth) of the vertices not frozen, each kept within
//!      `max_deviation` x diagonal of its input position; then exact checks
//!      (CGAL predicates): no degenerate face, no self-intersection, every
//!      component keeps the sign of its volume (shells stay shells, cavities
//!      cavities). Where one fails, the vertices of the offending faces that
//!      moved since the last check go back to their position then and are
//!      frozen for the remaining passes; repeat until the checks pass
//!      (always terminates: the state at the last check was valid);
//!   3. a final exact gate (require_closed_solid) on the result;
//!   4. the deviation: symmetric Hausdorff distance (CGAL bounded error) and
//!      area-weighted mean distance of the smoothed surface to the input
//!      (surface_deviation), plus the max vertex displacement, which bounds
//!      the Hausdorff distance (each point of a smoothed face is within it
//!      of the same barycentric point of the input face, and conversely).
//! Deterministic, identical for any thread count.
#pragma once

#include "subfab/core/progress.h"
#include "subfab/mesh/mesh.h"
#include "subfab/mesh/taubin_smooth.h"

namespace subfab {

//! Options of smooth_for_decomposition().
struct SmoothOptions {
  int num_passes = 100;         // Taubin (lambda, mu) passes (>= 0)
  double max_deviation = 0.005; // cap on each vertex's displacement from its input position, fraction of the
                                // bbox diagonal (>= 0); bounds the Hausdorff distance
  double lambda = 0.5;          // Taubin shrink factor, in (0, 1)
  double mu = -0.505;           // Taubin inflate factor, in (-1, -lambda); pass band k = 1/lambda + 1/mu = 0.02
                                // (Taubin's usual -0.53 gives 0.113, which keeps more detail: max_planck kept
                                // 69 blocks after 100 passes, against 46 with -0.505; bench/RESULTS.md)
  TaubinWeights weights = TaubinWeights::Uniform;  // Laplacian weights (see taubin_smooth.h)
  int check_every = 10;          // passes between two exact validity checks (>= 1); a vertex that makes a face
                                // invalid goes back to its position at the previous check
  double hausdorff_error = 1e-4; // error bound of the measured Hausdorff distance, fraction of the diagonal (> 0)
  Progress* progress = nullptr;  // stage "smooth", info lines; nullptr = silent
};

//! What smooth_for_decomposition() did and how far the result is from the input.
struct SmoothReport {
  int num_passes = 0;             // passes applied (some may have been partly backed off)
  int num_backoffs = 0;           // check/revert rounds that found invalid faces
  int num_vertices_frozen = 0;    // vertices reverted and frozen after a pass made a face invalid
  int num_vertices_moved = 0;     // vertices of the result not at their input position
  int num_vertices_capped = 0;    // vertices at the displacement cap at the end
  double bbox_diagonal = 0;       // of the input, model units
  double max_displacement = 0;    // max |result vertex - input vertex|, model units (>= hausdorff)
  double hausdorff = 0;           // symmetric Hausdorff distance input <-> result, model units, within
  double hausdorff_error = 0;     //   this absolute error bound (model units)
  double mean_deviation = 0;      // area-weighted mean distance of the moved surface to the input, model units
  double input_volume = 0;        // model units cubed
  double volume = 0;              // of the result, model units cubed
  double seconds = 0;             // wall time of the whole call
  double fraction(double x) const { return bbox_diagonal > 0 ? x / bbox_diagonal : 0; }
};

//! Result of smooth_for_decomposition().
struct SmoothResult {
  Mesh mesh;  // the smoothed solid: the input's vertices (same ids and count) and faces, positions moved
  SmoothReport report;
};

//! Low-pass filters a solid for the decomposition (Section 4.3.5), keeping
//! it a valid solid and measuring the deviation (see the file comment).
//! \param mesh triangle mesh, model units; an inward-oriented solid is
//!        flipped first (with a warning).
//! \throw InvalidMeshError if `mesh` is not a closed, manifold, consistently
//!        oriented, self-intersection-free solid (the reason and a remedy).
//! \throw InvalidArgumentError on invalid options.
//! \throw AlgorithmError if the result fails the final exact gate (a bug).
SmoothResult smooth_for_decomposition(const Mesh& mesh, const SmoothOptions& options);

}  // namespace subfab
