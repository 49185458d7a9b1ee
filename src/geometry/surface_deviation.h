// SPDX-License-Identifier: GPL-3.0-or-later
//! \file surface_deviation.h
//! Private: distance between a mesh and a locally modified copy of it, for
//! the report of repair_infeasible_features() (thesis Section 4.3.5 measures
//! faithfulness the same way: Hausdorff / mean distance to the input).
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! The face graph CGAL's distance queries run on (double coordinates).
using DistanceMesh = CGAL::Surface_mesh<CGAL::Exact_predicates_inexact_constructions_kernel::Point_3>;

//! Appends the listed faces of `mesh` (all when `faces` is null), in list
//! order, to `out`: vertices shared where the faces form a 2-manifold, copied
//! for a face that cannot be added otherwise (a patch pinched at a vertex;
//! distances do not depend on connectivity).
void append_distance_patch(DistanceMesh& out, const Mesh& mesh, const std::vector<int>* faces);

//! One-sided Hausdorff distance from `from` to `to` within `error` (model
//! units, > 0; CGAL's bounded-error algorithm): 0 when `from` is empty,
//! infinity when `to` is.
double one_sided_hausdorff(const DistanceMesh& from, const DistanceMesh& to, double error);

//! The parts inside the closed box `box` of `mesh`'s faces `faces`, each face
//! clipped to the box (Sutherland-Hodgman in doubles: a new corner lies a few
//! ulps of its coordinates from the face) and fanned into triangles: a soup,
//! for distance queries near the box that must not see a long face's far
//! parts (CAD parts' faces can span a third of the model).
Mesh clipped_faces(const Mesh& mesh, const std::vector<int>& faces, const BoundingBox& box);

struct SurfaceDeviation {
  double hausdorff = 0;  // symmetric Hausdorff distance, model units (CGAL bounded error, within `error_bound`)
  double mean = 0;       // area-weighted mean distance of the changed part of `modified` to `input`, model units
};

//! Deviation between `input` and `modified`, two surfaces that coincide
//! except on the faces `changed_input` of `input` and `changed_modified` of
//! `modified` (every other face of either is a face of the other).
//! Hausdorff = max(distance from the changed part of `modified` to `input`,
//! distance from the changed part of `input` to `modified`).
//! \param error_bound absolute error bound of the Hausdorff distance, model units (> 0).
SurfaceDeviation surface_deviation(const Mesh& input, const std::vector<int>& changed_input, const Mesh& modified,
                                   const std::vector<int>& changed_modified, double error_bound);

//! Deviation between `input` and `modified`, where `modified` and
//! `reference` share their faces, `reference` has `modified`'s connectivity
//! with every vertex at its corresponding point of the input surface (so it
//! describes the input surface; it may be `input` itself), and only the faces
//! in `changed` differ: max(distance from the changed faces of `modified` to
//! `input`, distance from the same faces of `reference` to `modified`); the
//! mean over the changed faces of `modified`.
SurfaceDeviation surface_deviation(const Mesh& input, const Mesh& reference, const Mesh& modified,
                                   const std::vector<int>& changed, double error_bound);

//! The faces of `a` that are not faces of `b` (same three corner positions
//! in the same cyclic order), in id order.
std::vector<int> faces_not_in(const Mesh& a, const Mesh& b);

}  // namespace subfab::detail
