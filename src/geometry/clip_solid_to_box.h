// SPDX-License-Identifier: GPL-3.0-or-later
//! \file clip_solid_to_box.h
//! Private: solid ∩ box, exactly, as closed 2-manifold exact meshes (the
//! clip step of carving, thesis Section 4.3.3; nothing in it is specific to
//! carving: any exact solid/box intersection can use it). Only the faces of
//! the solid near the box are converted to exact and corefined with the box
//! surface. Only .cpp files include it (CGAL stays out of public headers).
#pragma once

#include <vector>

#include "geometry/exact_mesh.h"
#include "geometry/solid_index.h"
#include "subfab/geometry/height_box.h"
#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! solid ∩ box, exactly, as closed 2-manifold pieces (pieces that touch
//! along an edge or at a vertex come out separately). Only the faces near
//! the box are converted and cut: the faces whose bounding box meets the
//! closed box form a patch whose border lies outside the box, the patch is
//! corefined with the box surface, and the block is bounded by the patch
//! faces inside the box plus the regions of the box surface inside the
//! solid (each region decided exactly at one of its border edges, from the
//! two solid faces on that edge).
//! `index` is the SolidIndex of `solid`; an empty result when the box has
//! zero volume or lies outside the solid. `solid` must be one the exact
//! booleans accept (no self-intersection, no zero-area face): CGAL 5.5's
//! corefinement can crash on others rather than throw, so a caller whose
//! mesh is not known to be such a solid (a block, not the checked input)
//! tests boolean_input_defect() first (remove_slivers.cpp,
//! single_precision_cleanup.cpp).
//! \throw AlgorithmError when the exact result cannot be made closed
//!        2-manifold pieces (a boolean failed).
std::vector<ExactMesh> clip_solid_to_box(const Mesh& solid, const SolidIndex& index, const Box3& box);

}  // namespace subfab::detail
