// SPDX-License-Identifier: GPL-3.0-or-later
//! \file local_infeasible_features.h
//! Private, exact test for the local features that make an exact
//! height-field box decomposition impossible in the current frame, whatever
//! the refinement (thesis Section 4.3.5, "Initialization constraints": a
//! triangle must lie in a valid box; refinement helps with triangles larger
//! than the local feature size, not with these).
//!
//! A face f can be covered after enough 1-to-4 refinement iff every child
//! can: the child at a corner v of f (similar to f, shrunk towards v), the
//! children along an edge e of f, and the interior children (always fine).
//! In the limit, only the faces around v (resp. e) can meet the child's
//! bounding box, so:
//! - CREASE (u, w): for the child of f along the edge (u, w) shared with g,
//!   the open bounding box near the edge is all of space in the
//!   coordinates that vary along the edge, and f's side of the plane in the
//!   coordinates that do not. If g enters it (its third vertex is strictly
//!   on f's side in every constant coordinate; always when the edge lies in
//!   no axis-aligned plane) and no axis is faced (exact n.d >= 0) by both f
//!   and g, no valid box covers f near the edge (the test of
//!   impossible_crease() in grow_boxes.cpp, extended to edges in axis planes).
//! - VERTEX v of f: the child's bounding box near v is the cone K of f's
//!   bounding box at v (a half-line in each coordinate where v is extreme in
//!   f, the solid's side where f is flat, the whole line otherwise). If no
//!   axis faced by f is faced by every other face around v that meets the
//!   open K (exact triangle/open-box test), no valid box covers f near v
//!   (a spike, a thin cone, a corner no box corner can isolate).
//! Every decision is exact (CGAL filtered predicates on the input doubles).
//!
//! TODO(merge): helper "orient" is writing the public exact feasibility test
//! (src/decompose/find_infeasible_features.*); merge this file into it.
#pragma once

#include <string>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! One infeasible feature.
struct LocalInfeasibleFeature {
  int vertex0 = -1;     // crease: first vertex of the edge (smaller id); vertex feature: the vertex
  int vertex1 = -1;     // crease: second vertex of the edge; vertex feature: -1
  int face = -1;        // a face that cannot be covered near the feature
  int other_face = -1;  // a face around the feature that blocks every box for `face`
  bool is_crease() const { return vertex1 >= 0; }
};

//! All infeasible creases (one entry per edge) and vertices (one entry per
//! vertex, the smallest blocked face), creases first, each list sorted by
//! vertex ids. Deterministic; parallel over faces.
//! \param mesh closed, manifold, oriented triangle mesh in the decomposition
//!        frame (n = (b - a) x (c - a) points out of the solid).
std::vector<LocalInfeasibleFeature> find_local_infeasible_features(const Mesh& mesh);

//! A sentence naming the feature (vertex ids, positions, faces).
std::string describe_feature(const Mesh& mesh, const LocalInfeasibleFeature& feature);

}  // namespace subfab::detail
