// SPDX-License-Identifier: GPL-3.0-or-later
//! \file triangulate_facets.h
//! Private: triangulation of the planar facets (with holes) of a PolyMesh,
//! for the OBJ export of facets with holes, the preview and the Hausdorff
//! distance. No new vertices are added.
#pragma once

#include <vector>

#include "subfab/mesh/mesh.h"
#include "subfab/unfold/poly_mesh.h"

namespace subfab::unfold_detail {

//! Triangles of `mesh` (vertices shared with the PolyMesh, same ids, CCW
//! from outside); face_facet[t] is the facet of triangle t.
Mesh triangulate_facets(const PolyMesh& mesh, std::vector<int>* face_facet = nullptr);

}  // namespace subfab::unfold_detail
