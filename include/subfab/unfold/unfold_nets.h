// SPDX-License-Identifier: GPL-3.0-or-later
//! \file unfold_nets.h
//! Stage 6 of the unfoldable simplification (thesis Section 3.3.3): cuts a
//! closed polygonal mesh into nets (a spanning forest of the facet adjacency
//! graph) and lays every net flat without overlaps.
//!
//! Outline:
//!   1. each facet gets an isometric 2D frame (outside up, so loops stay
//!      counter-clockwise); a child facet is placed by the 2D rigid motion
//!      that puts its fold edge on its parent's copy of that edge;
//!   2. a net grows greedily from a root: the best frontier edge (by the
//!      strategy's priority: longest fold edge, or normals ordered toward a
//!      direction as in the thesis) adds its facet if it overlaps no facet of
//!      the net (exact orientation predicates; touching is allowed); when
//!      nothing can be added, the next net starts at the largest facet left;
//!   3. small nets are then re-attached whole to another net across any
//!      shared edge when that creates no overlap, smallest first;
//!   4. several roots x strategies are tried (in parallel) and the result
//!      with the fewest nets (then the largest net) is kept: deterministic.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/unfold/poly_mesh.h"

namespace subfab {

using Vec2 = Eigen::Vector2d;

//! Options of unfold_nets().
struct UnfoldNetsOptions {
  int num_roots = 4;            // largest facets tried as first root
  bool merge_small_nets = true; // step 3 above
  Progress* progress = nullptr; // may be null
};

//! A fold: an edge of the mesh kept uncut inside a net.
struct Fold {
  int parent = -1, child = -1;  // facet ids; child hangs from parent in the net's tree
  int v0 = -1, v1 = -1;         // vertex ids: the edge runs v0 -> v1 in the parent's loop
  double dihedral_deg = 0;      // interior angle between the two facets (inside the solid), degrees
};

//! A net: facets laid out together in one flat piece.
struct Net {
  int root = -1;
  std::vector<int> facets;  // root first, then in placement order
  double area = 0;          // model units^2
};

//! Result of unfold_nets().
struct Unfolding {
  //! positions[f][l][i]: 2D position (model units) of corner i of loop l of
  //! facet f, same loops and order as the PolyMesh (counter-clockwise outer).
  std::vector<std::vector<std::vector<Vec2>>> positions;
  std::vector<int> net_of_facet;  // net index per facet
  std::vector<int> parent_fold;   // index into folds of the fold to the parent, -1 for roots
  std::vector<Fold> folds;
  std::vector<Net> nets;
};

//! Unfolds `mesh` into nets (thesis Section 3.3.3).
//! \param mesh closed, manifold polygonal mesh (facet normals need not be
//!        lattice directions; each facet must be planar).
//! \throw InvalidMeshError when an edge has no opposite (mesh not closed).
Unfolding unfold_nets(const PolyMesh& mesh, const UnfoldNetsOptions& options = {});

//! Interior dihedral angle (degrees, in (0, 360)) at the edge v0 -> v1 of
//! facet a, whose other side is facet b: 180 - angle(normals) when convex.
double dihedral_angle_deg(const PolyMesh& mesh, int a, int b, int v0, int v1);

//! Facets of one net whose interiors overlap in 2D (exact predicates; shared
//! edges and touching points are fine). Returns "" when none, else the first pair.
std::string find_net_overlap(const Unfolding& unfolding);

//! Refolds every net from its 2D positions, its tree of folds and their
//! dihedral angles (each root placed by a rigid fit) and returns the largest
//! distance between a refolded corner and the mesh corner (model units).
double refold_error(const PolyMesh& mesh, const Unfolding& unfolding);

}  // namespace subfab
