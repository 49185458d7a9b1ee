// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_closed_manifold.h
//! Private: the exact closed-manifold check of an ExactPolyMesh, run by facet
//! deletion (thesis Section 3.3.2) after every deletion and by
//! check_poly_mesh().
#pragma once

#include <string>

#include "unfold/exact_poly_mesh.h"

namespace subfab::unfold_detail {

//! Closed (every directed edge has exactly one opposite), no edge used twice
//! in the same direction, every vertex a single fan. Returns "" when fine,
//! otherwise the first problem. Only alive facets count.
std::string check_closed_manifold(const ExactPolyMesh& mesh);

}  // namespace subfab::unfold_detail
