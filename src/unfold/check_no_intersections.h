// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_no_intersections.h
//! Private: the exact intersection checks of an ExactPolyMesh's facets, run
//! by facet deletion (thesis Section 3.3.2) after every deletion and by
//! check_poly_mesh(): each facet simple, and no two facets meeting except
//! along shared edges and at shared vertices.
#pragma once

#include <string>
#include <vector>

#include "unfold/exact_poly_mesh.h"

namespace subfab::unfold_detail {

enum class Where { Outside, Boundary, Inside };
//! Where a point of the facet's plane lies relative to the facet (exact).
Where locate_in_facet(const ExactPolyMesh& mesh, const QFacet& facet, const QVec& p);

//! A facet is simple: no repeated vertex, no two of its edges meet except
//! consecutive ones at their common vertex, all vertices on its plane, outer
//! loop positive area, holes negative and inside the outer loop.
std::string check_facet_simple(const ExactPolyMesh& mesh, int f);

//! Two facets intersect only along shared edges and at shared vertices.
//! Returns "" when fine.
std::string check_facet_pair(const ExactPolyMesh& mesh, int a, int b);

//! Checks `facets` (ids) against every alive facet whose bounding box
//! touches theirs; "" when all fine. Pass all ids for a global check.
std::string check_no_intersections(const ExactPolyMesh& mesh, const std::vector<int>& facets);

}  // namespace subfab::unfold_detail
