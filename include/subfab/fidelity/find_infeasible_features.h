// SPDX-License-Identifier: GPL-3.0-or-later
//! \file find_infeasible_features.h
//! Places of a surface that no axis-aligned height-field box can ever cover,
//! in a given frame, however finely the mesh is refined (thesis Section 4.3.2
//! "Initialization" and 4.3.5 "Initialization constraints": the thesis assumes
//! that one-to-four refinement always makes a triangle's bounding box a valid
//! block; at sharp creases and spikes that no axis sees it never does).
//!
//! A box B is valid for a milling axis a when no face facing away from a
//! (n.a < 0, exact sign) meets B's open interior; a face f is covered by B
//! when f lies in B and faces a (see solid_index.h). Thin features (a far
//! piece of surface inside a triangle's bounding box) disappear under
//! refinement; what remains are LOCAL obstructions, decided exactly from the
//! cone of the surface at a point:
//!
//! - Edge (u, v) between faces f and g. Some child of f (after any
//!   refinement) contains a segment of the edge, so its box contains the
//!   cone K of f's half-plane at the edge: the whole line of the edge and,
//!   in each coordinate where u and v agree, the half-line towards f's third
//!   vertex (or, when f lies in that coordinate plane, towards the solid).
//!   The edge is infeasible for f when g meets the open cone and f and g
//!   have no common facing axis. (When no coordinate of u and v agrees this
//!   is the "impossible crease" that grow_boxes() detects.)
//! - Vertex p and face f of its star. One-to-four refinement keeps f's
//!   corner at p similar to itself, so the corner child's box contains the
//!   smallest orthant-like cone K containing f's corner sector (per
//!   coordinate: [0, inf), (-inf, 0], or both when the sector spans both
//!   signs; a coordinate plane f lies in is thickened towards the solid).
//!   The vertex is infeasible for f when, for every axis f faces, some face
//!   of the star facing away from it meets p + the open cone (the thin spike
//!   or cone tip seen by no axis). Such a vertex is marked `splittable` when
//!   splitting every blocked corner along the coordinate planes through p
//!   would make each piece coverable (its cone is then one closed orthant);
//!   otherwise no refinement at all can cover it.
//!
//! Both tests are exact (comparisons of doubles, exact orientation
//! predicates) and deterministic; the whole scan is linear in the mesh size
//! (parallel over vertices).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! One infeasible feature.
struct InfeasibleFeature {
  enum class Kind { Edge, Vertex };
  Kind kind = Kind::Edge;
  int vertex0 = -1;  // the vertex, or the edge's first end (smaller id)
  int vertex1 = -1;  // the edge's second end (-1 for a vertex)
  int face = -1;     // a face that cannot be covered there
  int blocking_face = -1;  // a face of the star that blocks it (facing away, inside every box)
  // Vertex only: each blocked corner could be covered if split along the
  // coordinate planes through the vertex (pieces in one orthant each), which
  // one-to-four refinement never does; false when some piece is blocked too.
  bool splittable = false;
};

//! Options of find_infeasible_features().
struct FeasibilityOptions {
  bool check_edges = true;     // edge (crease) test
  bool check_vertices = true;  // vertex (corner / spike) test
  // Local test: only the corners at these vertex ids and the edges with an end
  // among them (each once); empty = every vertex. Given the vertices of every
  // face an edit changed (before and after it), the difference of the two
  // local counts is that of the whole mesh, at the cost of the region only.
  std::vector<int> only_vertices;
  // Within a tolerance (issue 17): per face, bit k set when the face may
  // lean past vertical along axis k (tolerance_allowances()): it then counts
  // as facing both +e_k and -e_k, as the decomposition's stages treat it, so
  // it neither blocks a box along that axis nor lacks a common axis with its
  // neighbour there. nullptr (default): exact normal signs only. When given,
  // it must have one entry per face.
  const std::vector<std::uint8_t>* allowed_overhangs = nullptr;
};

//! Result of find_infeasible_features().
struct FeasibilityResult {
  std::vector<InfeasibleFeature> features;  // edges (by smaller then larger end id), then vertices (by id)
  std::size_t num_edges = 0;     // infeasible edges
  std::size_t num_vertices = 0;  // infeasible vertices
  std::size_t num_splittable_vertices = 0;  // of which every blocked corner could be covered once split
  std::size_t size() const { return features.size(); }
  bool feasible() const { return features.empty(); }
};

//! Lists the edges and vertices of `mesh` (in its own frame) where no valid
//! axis-aligned height-field box can cover the adjacent faces, whatever the
//! refinement (see the file comment; thesis 4.3.2 / 4.3.5). Each infeasible
//! edge or vertex is listed once, with the first face (by id) it blocks.
//! \param mesh closed, manifold, consistently oriented (outward normals)
//!        triangle mesh; #V vertices, #F faces.
//! With `options.only_vertices`, only that region is scanned (see
//! FeasibilityOptions), in time proportional to its stars plus one pass over
//! the face list.
//! \throw InvalidMeshError if an edge has no opposite directed edge.
//! \throw InvalidArgumentError if a vertex id of the region is out of range.
FeasibilityResult find_infeasible_features(const Mesh& mesh, const FeasibilityOptions& options = {});

//! Human-readable list of the first `max_listed` features with positions
//! taken from `positions` (e.g. the input mesh, same vertex ids), such as
//! "edge (x y z)-(x y z), vertex (x y z)".
std::string describe_infeasible_features(const FeasibilityResult& result, const Mesh& positions,
                                         std::size_t max_listed = 3);

}  // namespace subfab
