// SPDX-License-Identifier: GPL-3.0-or-later
//! \file merge_coplanar_neighbours.h
//! Private: the clean-ups facet deletion (thesis Section 3.3.2) runs after
//! closing a hole, on an ExactPolyMesh: adjacent facets on one plane become
//! one facet, and vertices left on a straight edge between two facets go.
#pragma once

#include <optional>
#include <vector>

#include "unfold/exact_poly_mesh.h"

namespace subfab::unfold_detail {

//! Merges adjacent facets on the same plane with the same normal
//! (re-tracing the loops), for every adjacency that involves a facet of
//! `only` (all facets when `only` is empty). Returns the ids of facets that
//! changed, or nullopt when a merged region could not be traced (pinched).
std::optional<std::vector<int>> merge_coplanar_neighbours(ExactPolyMesh& mesh, const std::vector<int>& only = {});

//! Removes vertices where only two facets meet (they lie on a straight edge
//! between the two). Returns the ids of facets that changed.
std::vector<int> remove_two_facet_vertices(ExactPolyMesh& mesh);

//! True when some pair of adjacent alive facets lies on one plane with one
//! normal (should never be after merge_coplanar_neighbours).
bool has_coplanar_neighbours(const ExactPolyMesh& mesh);

}  // namespace subfab::unfold_detail
