// SPDX-License-Identifier: GPL-3.0-or-later
//! \file restore_details.h
//! Thesis Section 4.3.5 ("Faithfulness vs Complexity"), second step: after
//! the height-field decomposition of the smoothed model
//! (smooth_for_decomposition()), the details the smoothing removed are put
//! back under the decomposition's fabrication constraints, by a Laplacian
//! surface reconstruction [Sorkine 2006] with the original's differential
//! coordinates:
//!
//!   argmin ||L v - delta||^2 + w^2 sum_{free i} ||v_i - o_i||^2        (4.6)
//!   s.t. v_i in the box of the region holding vertex i               (4.7)
//!        n_t(v) . m >= 0 for the direction m of each region of face t (4.8)
//!
//! L is the uniform Laplacian ((L v)_i = v_i - mean of its neighbours),
//! delta = L o the original's differential coordinates, w the (small) soft
//! anchor that fixes the translation. The thesis solves it by coordinate
//! descent with Newton steps; here the quadratic part is one sparse least
//! squares solve (Eigen SimplicialLDLT on the normal equations) and the
//! inequalities are handled by an active set: vertices that leave their box
//! are held on it, vertices of faces that break (4.8) go back towards their
//! smoothed position, and the rest is solved again.
//!
//! Outline of restore_details():
//!   1. each vertex's region: the first box, in carve order, holding its
//!      smoothed position (the region B_i \ (B_0 u ... u B_{i-1}) of
//!      carve_blocks()); a vertex no box holds stays at its smoothed position;
//!   2. each face's directions: the axes of its vertices' regions along which
//!      the smoothed face faces (exact sign of n.d >= 0; a direction the
//!      smoothed face does not face belongs to a region the face only touches);
//!   3. repeat: solve (4.6) for the free vertices, the held ones fixed; hold
//!      every free vertex outside its box (or its `room`) at its projection on
//!      it; then
//!      exact checks of the whole mesh: faces breaking (4.8) (exact normal
//!      signs), zero-area faces and self-intersecting pairs (CGAL); each of
//!      their vertices is held at the point halfway back towards its smoothed
//!      position (after `max_halvings` such moves: at its smoothed position),
//!      until no check fails and no vertex left its box. Always terminates: a
//!      face whose vertices are all at their smoothed positions passes every
//!      check (the smoothed mesh is a valid solid and faces its directions).
//! The result is a valid solid (closed, no zero-area face, no
//! self-intersection) whose faces face every direction assigned to them; the
//! blocks are then carved again from it with the same boxes (the caller:
//! decompose_smoothed()), where the exact block checks have the last word.
//! Deterministic, identical for any thread count.
#pragma once

#include <cstddef>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/geometry/height_box.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of restore_details().
struct RestoreDetailsOptions {
  double anchor_weight = 1.0;  // w in (4.6): pull of each free vertex towards its original position, relative to
                               // the unit diagonal of the uniform Laplacian (> 0); smaller bends the detail more
                               // smoothly around held vertices, larger keeps it closer to its original place
  int max_halvings = 3;        // moves halfway back towards the smoothed position before a vertex of a failing
                               // face is held at the smoothed position itself (>= 0)
  const std::vector<HeightBox>* room = nullptr;  // per box, the box the vertices of its region may move in
                                                 // (e.g. the box grown where no later box loses material);
                                                 // nullptr = the box itself. Regions are assigned with `boxes`.
  const std::vector<int>* held = nullptr;  // vertices to keep at their smoothed positions from the start (e.g.
                                           // where a carve of an earlier restoration failed); nullptr = none
  Progress* progress = nullptr;  // info lines; nullptr = silent
};

//! What restore_details() did.
struct RestoreDetailsReport {
  int num_rounds = 0;              // solves of (4.6)
  int num_outside_boxes = 0;       // vertices no box holds (kept at their smoothed positions)
  int num_held_on_box = 0;         // vertices held on the boundary of their box (4.7)
  int num_held_back = 0;           // vertices moved back towards their smoothed position by a failing face
  int num_at_smoothed = 0;         // vertices of the result at their smoothed position
  int num_restored = 0;            // vertices of the result within 1e-9 x diagonal of their original position
  int num_face_failures = 0;       // faces that broke (4.8), summed over rounds
  int num_solid_failures = 0;      // zero-area or self-intersecting faces, summed over rounds
  double max_displacement_smoothed = 0;  // max |smoothed vertex - original vertex|, model units
  double max_displacement = 0;           // max |result vertex - original vertex|, model units
  double mean_displacement_smoothed = 0; // mean of the same, model units
  double mean_displacement = 0;          // mean |result vertex - original vertex|, model units
  double seconds = 0;                    // wall time
};

//! Result of restore_details().
struct RestoreDetailsResult {
  Mesh mesh;                 // the restored solid: the original's faces, vertices moved (same ids and count)
  std::vector<int> region;   // per vertex: the box index of its region (-1: none holds it)
  RestoreDetailsReport report;
};

//! Puts the details of `original` back into `smoothed` within the regions of
//! `boxes` (see the file comment; thesis Section 4.3.5).
//! \param original the input solid (model units, the frame of the boxes)
//! \param smoothed the same mesh smoothed: same faces, same number of vertices,
//!        a valid solid (closed, no zero-area face, no self-intersection)
//! \param boxes    the decomposition's boxes in carve order (the frame of both meshes)
//! \throw InvalidArgumentError when the meshes do not share their faces and
//!        vertex count, or on bad options.
RestoreDetailsResult restore_details(const Mesh& original, const Mesh& smoothed, const std::vector<HeightBox>& boxes,
                                     const RestoreDetailsOptions& options = {});

}  // namespace subfab
