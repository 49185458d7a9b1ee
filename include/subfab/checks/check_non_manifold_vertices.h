// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_non_manifold_vertices.h
//! Input check: no pinched vertex.
#pragma once

#include "subfab/checks/check_result.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Finds vertices whose incident faces form more than one fan (faces
//! connected through edges at the vertex), e.g. two cones touching at their
//! tips. Examples are vertex ids.
//! \throw InvalidMeshError when a face index is out of range (run
//!        check_face_indices() first).
CheckResult check_non_manifold_vertices(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace subfab
