// SPDX-License-Identifier: GPL-3.0-or-later
//! \file delete_facets.h
//! Stage 5 of the unfoldable simplification (thesis Section 3.3.2): removes
//! facets from a closed polygonal mesh whose normals are lattice directions
//! and closes each hole by extending the neighbouring facet planes.
//!
//! Outline, per deleted facet (or set of adjacent facets, Figure 3.11):
//!   1. the facets around the hole form a circular buffer (one entry per
//!      neighbour, in boundary order); each adjacent pair of the buffer meets
//!      at a surviving vertex, from which a half-line runs along the line
//!      where their two planes meet;
//!   2. among all triplets (a, b, c) of consecutive buffer entries, the two
//!      half-lines in b's plane are intersected; the closest valid
//!      intersection closes b (two new edges meet there), b leaves the
//!      buffer, and a and c get a new half-line from that point;
//!   3. repeat until two entries remain (they meet along one line) or three
//!      whose half-lines meet in one point.
//! Every construction is exact (rationals: planes n.x = c with integer n),
//! and after every deletion the mesh is checked exactly: closed, manifold,
//! every facet simple and planar, no two facets intersecting except along
//! shared edges and vertices, no coplanar neighbours (they are merged). A
//! deletion that fails any of this is undone and reported.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/unfold/poly_mesh.h"

namespace subfab {

//! Options of delete_facets().
struct DeleteFacetsOptions {
  //! Facets with area below this are deleted automatically (model units^2);
  //! 0 = none. The unfold command uses 2 x grid spacing^2 by default.
  double min_facet_area = 0;
  //! Facet ids (into the input mesh) to delete explicitly; adjacent ids are
  //! deleted together as one group. Deleted before the automatic pass.
  std::vector<int> facet_ids;
  //! Lattice frame: every vertex is grid_origin + grid_step * m / 24 for
  //! integers m (model units). grid_step = 0: coordinates are exact as given.
  Vec3 grid_origin = Vec3::Zero();
  double grid_step = 0;  // model units
  //! A deletion is refused when a new vertex lies farther than this from
  //! every vertex of the deleted facets (model units); 0 = no limit.
  double max_extension = 0;
  //! When set, a deletion is refused when a new vertex lies farther than
  //! max_distance_to_reference from this surface (model units): keeps the
  //! simplified mesh close to the input (the unfold command passes the input
  //! mesh and 1.5 x grid spacing).
  const Mesh* reference = nullptr;
  double max_distance_to_reference = 0;  // model units
  //! Automatic pass: when a small facet cannot be deleted alone, it is tried
  //! together with up to (max_group_size - 1) adjacent facets whose area is
  //! below group_area_factor x min_facet_area.
  int max_group_size = 3;          // facets
  double group_area_factor = 4.0;  // dimensionless
  Progress* progress = nullptr;    // stage progress and warnings; may be null
};

//! A deletion that could not be done, and why.
struct FacetDeletionFailure {
  std::vector<int> facets;  // ids in the input mesh
  std::string reason;
};

//! Result of delete_facets().
struct DeleteFacetsResult {
  PolyMesh mesh;                // closed, manifold, facets renumbered 0..n-1
  std::size_t num_deleted = 0;  // facets of the input that were deleted
  std::size_t num_merged = 0;   // facets that disappeared by coplanar merging
  std::vector<FacetDeletionFailure> failures;  // explicit ids that stayed, and small facets that stayed
};

//! Deletes facets (explicit ids first, then every facet smaller than
//! options.min_facet_area, smallest first, repeated until nothing changes)
//! and closes the holes as described above (thesis Section 3.3.2).
//! \param mesh closed polygonal mesh with every facet normal a lattice
//!        direction and every vertex on the lattice frame of the options.
//! \throw InvalidArgumentError when a vertex is off the lattice frame, a
//!        facet is not planar or its normal is not a lattice direction, or
//!        an explicit id is out of range.
//! \throw InvalidMeshError when the input itself is not closed and manifold.
DeleteFacetsResult delete_facets(const PolyMesh& mesh, const DeleteFacetsOptions& options);

//! Exact validity check of a polygonal mesh on a lattice frame (see
//! DeleteFacetsOptions::grid_origin/grid_step): closed, manifold, facets
//! simple and planar with outer loops counter-clockwise from outside, normals
//! lattice directions, adjacent facets never coplanar, no self-intersections.
//! Returns "" when valid, otherwise the first problem found.
std::string check_poly_mesh(const PolyMesh& mesh, const Vec3& grid_origin, double grid_step);

}  // namespace subfab
