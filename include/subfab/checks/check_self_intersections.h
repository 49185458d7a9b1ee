// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_self_intersections.h
//! Input check: the surface does not intersect itself (exact, CGAL).
#pragma once

#include "subfab/checks/check_result.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Finds pairs of faces that intersect other than along the vertices and
//! edges they share: candidate pairs from CGAL's box intersection on face
//! bounding boxes, then exact CGAL predicates, in parallel (parallel_for,
//! result independent of the thread count). Faces touching through two
//! vertices with different ids at the same position do intersect.
//! Degenerate faces (see check_degenerate_faces()) are not tested.
//! num_offending counts intersecting pairs; examples are the face ids of the
//! first pairs (in face order).
//! \throw InvalidMeshError when an index is out of range or a coordinate is
//!        not finite (run those checks first).
CheckResult check_self_intersections(const Mesh& mesh, const CheckOptions& options = {});

//! The number of intersecting pairs, as check_self_intersections() counts
//! them, that hold at least one of `faces` (ids into mesh.faces, each once):
//! what moving vertices of those faces alone can change. Each of `faces` is
//! tested against every face whose bounding box meets its own (a linear scan:
//! for a few faces this is far cheaper than the whole check). Sequential.
//! \throw InvalidMeshError as check_self_intersections(); InvalidArgumentError
//!        when a face id is out of range.
std::size_t count_self_intersections_of(const Mesh& mesh, const std::vector<int>& faces);

}  // namespace subfab
