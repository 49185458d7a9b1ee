// SPDX-License-Identifier: GPL-3.0-or-later
//! \file repair_infeasible_features.h
//! Local repair of the features that make an exact height-field box
//! decomposition impossible in the decomposition frame (thesis Section
//! 4.3.5: "Faithfulness vs Complexity" trades a small, reported deviation
//! for a decomposable input; "Initialization constraints" for the 1-to-4
//! refinement). Unlike the thesis's global low-pass filter, only a small
//! band around each feature moves.
//!
//! A feature is infeasible when refinement can never help (see
//! find_infeasible_features(), exact): a crease whose two
//! sides no axis-aligned direction sees together (normals more than 90
//! degrees apart, edge in no axis-aligned plane), or a vertex whose
//! surrounding faces no box corner can separate (a spike or thin cone).
//!
//! Outline of repair_infeasible_features():
//!   1. features = exact local test; none: return the input unchanged;
//!   A. local edits, each kept only if the exact test then finds strictly
//!      fewer features (so this stage moves towards feasibility and ends;
//!      the test is run on the edited region only, whose count difference is
//!      the whole mesh's), tried per feature, cheapest first:
//!      - a "splittable" vertex: split its faces along the coordinate planes
//!        through it (no deviation);
//!      - move one vertex (the feature's, then a neighbour): towards the
//!        centroid of its neighbours, onto the line of two neighbours (a
//!        straightened crease), onto the plane of a face across its link,
//!        or to the nearest position where its whole star faces one axis
//!        (exact half-spaces: the normal is linear in the vertex), so the
//!        axis sees the vertex and its edges;
//!      - Laplacian smoothing of a disc of 1 to 3 rings around the feature;
//!      - once refinement is exhausted (below), a chamfer of a sharp ridge
//!        at a feature vertex (a peak of the ridge,
//!        where both sides reach into one orthant and no axis sees them
//!        together): its faces are split into two sides at two link
//!        vertices a, b, the vertex is doubled, each copy moved 1/32, 1/8 or
//!        1/2 of the way into its side, and a strip of two faces (a, p, p'),
//!        (b, p', p) joins them: each side's star can then face its own axis
//!        and the strip faces one axis of each;
//!      moves are limited to 1/16, then 1/4, then all of the deviation cap;
//!      when no edit helps, the stars of the remaining features are refined
//!      one-to-four (at most 6 levels, a few hundred faces per feature) and
//!      the edits are tried again; after the last level, once more with the
//!      chamfer;
//!   B. if features remain, start again from the input with rounds of band
//!      refinement and smoothing (sharp creases that need a fillet of many
//!      strips); repeat (at most `max_rounds` times, and giving up after
//!      `max_stalled_rounds` rounds that do not reduce the number of
//!      features below its best) while features remain:
//!      a. band = faces within `band_rings` edge rings of the feature
//!         vertices (one ring more every `widen_every` rounds);
//!      b. refine the band one-to-four (conforming, refine_mesh) until the
//!         faces within a few target edges of a feature vertex have their
//!         longest edge below `edge_length` x bbox diagonal;
//!      c. Taubin smoothing (uniform weights, lambda, mu) of the band's vertices, the rest
//!         fixed: each crease becomes a fillet of small creases, each seen by
//!         an axis, each spike a blunt tip; coordinates shared by a vertex
//!         and all its neighbours (axis-aligned flats) are kept exactly;
//!      d. every vertex keeps a reference point on the input surface (its
//!         input position, or the midpoint of its edge's reference points),
//!         so max |vertex - reference| bounds the Hausdorff distance; over
//!         `max_deviation`: AlgorithmError;
//!      e. features = exact local test on the new mesh;
//!   3. the result must still be a closed, manifold, outward-oriented,
//!      non-degenerate, self-intersection-free solid (exact checks), else
//!      AlgorithmError;
//!   4. report: features found, vertices moved, Hausdorff distance (CGAL
//!      bounded-error, between the changed patches and the other mesh) and
//!      the area-weighted mean distance of the changed surface to the input.
//! Deterministic, identical for any thread count.
#pragma once

#include "subfab/core/progress.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of repair_infeasible_features().
struct RepairOptions {
  int max_rounds = 40;          // rounds of local edits (A), then of refine/smooth (B), before giving up
  double max_deviation = 0.005; // cap on the deviation from the input, fraction of the bbox diagonal (> 0)
  double edge_length = 0.004;   // band faces are refined until their longest edge is below this, fraction of
                                // the bbox diagonal (> 0); sets the fillet size (a few such lengths)
  int band_rings = 2;           // edge rings around feature vertices that are refined and smoothed (>= 1)
  int widen_every = 4;          // the band grows by one ring every this many rounds (>= 1)
  int max_stalled_rounds = 4;   // B gives up after this many rounds without fewer features than its best (>= 1)
  int smoothing_steps = 10;     // Taubin (lambda, mu) step pairs per round (>= 1)
  double lambda = 0.5;          // Taubin shrink factor, in (0, 1)
  double mu = -0.53;            // Taubin inflate factor, < -lambda (no shrinkage, Taubin 1995); 0 = plain Laplacian
  Progress* progress = nullptr; // info lines (features, rounds, deviation); nullptr = silent
};

//! What repair_infeasible_features() found and changed.
struct RepairReport {
  int num_features = 0;          // infeasible features in the input (creases + vertices)
  int num_creases = 0;           // of which infeasible crease edges
  int num_vertices = 0;          // of which infeasible vertices
  int num_rounds = 0;            // refine/smooth rounds used (0 if nothing to repair)
  int num_faces_removed = 0;     // faces of the input that are not faces of the result
  int num_faces_new = 0;         // faces of the result that are not faces of the input (the repaired patches)
  double bbox_diagonal = 0;      // of the input, model units
  double max_deviation = 0;      // symmetric Hausdorff distance input <-> result, model units (within hausdorff_error)
  double hausdorff_error = 0;    // error bound of max_deviation, model units
  double mean_deviation = 0;     // area-weighted mean distance of the changed surface to the input, model units
  double max_deviation_fraction() const { return bbox_diagonal > 0 ? max_deviation / bbox_diagonal : 0; }
  double mean_deviation_fraction() const { return bbox_diagonal > 0 ? mean_deviation / bbox_diagonal : 0; }
};

//! Result of repair_infeasible_features().
struct RepairResult {
  Mesh mesh;           // repaired mesh (the input, bit for bit, if it had no infeasible feature): input vertices
                       // keep their ids, new vertices are appended; faces away from the features are unchanged
  RepairReport report;
};

//! Removes every infeasible feature of `mesh` by local refinement and
//! smoothing (Section 4.3.5, local version; see the file comment).
//! \param mesh closed, manifold, outward-oriented, self-intersection-free
//!        triangle mesh IN THE DECOMPOSITION FRAME (after orient: the
//!        features depend on the frame), model units.
//! \return the repaired mesh (same frame and units) and the report; after
//!         it find_infeasible_features() finds nothing.
//! \throw InvalidArgumentError on invalid options.
//! \throw AlgorithmError naming a feature if it cannot be repaired within
//!        `max_rounds` and `max_deviation`, or if the repaired mesh would not
//!        be a valid solid.
RepairResult repair_infeasible_features(const Mesh& mesh, const RepairOptions& options);

}  // namespace subfab
