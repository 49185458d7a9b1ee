// SPDX-License-Identifier: GPL-3.0-or-later
//! \file taubin_smooth.h
//! Taubin's lambda/mu low-pass filter of a triangle mesh (G. Taubin, "A
//! signal processing approach to fair surface design", SIGGRAPH 1995), the
//! filter thesis Section 4.3.5 ("Faithfulness vs Complexity") applies before
//! the decomposition to remove the high-frequency details that each need a
//! block of their own (Section 4.4.4).
//!
//! One pass = a shrinking Laplacian step p += lambda * L(p) followed by an
//! inflating step p += mu * L(p) (mu < -lambda < 0), where L(p) is the
//! weighted mean of the neighbours minus p. Its transfer function
//! (1 - lambda k)(1 - mu k) is ~1 below the pass-band frequency
//! k_PB = 1/lambda + 1/mu (0.113 for the defaults) and < 1 above it: the
//! shape and volume are kept, the small details decay.
//!
//! Pure geometry, no validity check: the positions may come out
//! self-intersecting. smooth_for_decomposition() (decompose module) wraps it
//! with exact checks and backs off where needed.
#pragma once

#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! Weights of the discrete Laplacian L(p) = sum_j w_ij (p_j - p_i), sum_j w_ij = 1.
enum class TaubinWeights {
  //! w_ij = 1 / degree (Taubin 1995's "umbrella" operator). The default: its
  //! eigenvalues lie in [0, 2], so the filter is stable for any lambda in
  //! (0, 1) and mu > -1 on any mesh, and Taubin's frequency analysis is
  //! exact for it. It also has a tangential component that evens out the
  //! sampling (vertices drift along the surface; the drift counts against
  //! the displacement cap but does not change the surface much).
  Uniform,
  //! Cotangent weights (cot alpha + cot beta) / 2, clamped at zero (obtuse
  //! pairs would be negative) and normalised per vertex; a vertex whose
  //! clamped weights sum to zero uses uniform weights. Moves mostly along
  //! the normal (mean-curvature flow), so less of the cap is spent on
  //! tangential drift; recomputed from the current positions at each step.
  Cotangent,
};

//! Options of taubin_smooth().
struct TaubinOptions {
  int num_passes = 10;                  // (lambda, mu) step pairs (>= 0)
  double lambda = 0.5;                  // shrink factor, in (0, 1)
  double mu = -0.53;                    // inflate factor, in (-1, -lambda) (Taubin: no shrinkage); 0 = plain
                                        // Laplacian (shrinks)
  TaubinWeights weights = TaubinWeights::Uniform;  // Laplacian weights (see TaubinWeights)
  double max_displacement = std::numeric_limits<double>::infinity();  // cap on |p - anchor| per vertex after
                                        // every step, model units (>= 0): the vertex is pulled back radially
                                        // towards its anchor; the cap holds exactly (computed distance <= cap)
  bool keep_axis_aligned = true;        // a coordinate the vertex shares exactly with all its neighbours (an
                                        // axis-aligned flat or line) is not changed by that step
  std::span<const Vec3> anchors = {};   // #V positions the cap is measured from (e.g. the input's when the
                                        // filter runs in several calls); empty = the positions at the call
};

//! What taubin_smooth() did.
struct TaubinReport {
  int num_passes = 0;               // (lambda, mu) pairs applied
  int num_capped = 0;               // movable vertices that ended at the displacement cap
  double max_displacement = 0;      // max |p - anchor| over the movable vertices at the end, model units
};

//! Low-pass filters the positions of `mesh` in place (Taubin 1995;
//! thesis Section 4.3.5). Every vertex moves; see the overload for a subset.
//! \param mesh triangle mesh (any: open, several components), model units;
//!        connectivity unchanged, only positions move.
//! \throw InvalidArgumentError on invalid options, out-of-range face
//!        indices or anchors of the wrong size.
TaubinReport taubin_smooth(Mesh& mesh, const TaubinOptions& options);

//! Same, but only the vertices listed in `movable` move; the others are fixed
//! (they still pull their neighbours). For local smoothing (a band around a
//! feature) and to freeze vertices the caller has backed off.
//! \param movable vertex ids (any order, duplicates ignored), each in [0, #V).
//! Deterministic, identical for any thread count (Jacobi steps, one output
//! slot per vertex).
TaubinReport taubin_smooth(Mesh& mesh, std::span<const int> movable, const TaubinOptions& options);

}  // namespace subfab
