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

}  // namespace subfab
