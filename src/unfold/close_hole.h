// SPDX-License-Identifier: GPL-3.0-or-later
//! \file close_hole.h
//! Private: closing the hole that deleting facets leaves, by extending the
//! planes of the facets around it (thesis Section 3.3.2, Figure 3.11; the
//! outline is in subfab/unfold/delete_facets.h). Every construction is exact.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "geometry/hausdorff_distance.h"
#include "unfold/exact_poly_mesh.h"

namespace subfab::unfold_detail {

//! How far the new vertices of a closed hole may lie from the old surface.
struct CloseHoleLimits {
  //! A new vertex must lie this close to some vertex of the deleted facets
  //! (model units); 0 = no limit.
  double max_extension = 0;
  //! When set, a new vertex must lie within max_distance of this surface
  //! (the input mesh); null = no limit.
  const detail::SurfaceDistance* reference = nullptr;
  double max_distance = 0;  // model units
};

//! Deletes the facets `region` (ids of alive facets without holes, forming a
//! disk) and closes the hole by extending the neighbouring facets' planes.
//! `owner` maps every directed edge of an alive facet (edge_key) to its facet.
//! Returns "" on success (mesh modified, region facets dead), else the reason
//! (mesh possibly half-modified: the caller restores it). Does not merge or
//! validate: see try_delete in delete_facets.cpp.
std::string close_hole(ExactPolyMesh& mesh, const std::unordered_map<std::uint64_t, int>& owner,
                       const std::vector<int>& region, const CloseHoleLimits& limits);

}  // namespace subfab::unfold_detail
