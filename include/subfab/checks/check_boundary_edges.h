// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_boundary_edges.h
//! Input check: the mesh is closed (every edge has two faces or more).
#pragma once

#include "subfab/checks/check_result.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Finds boundary edges (used by exactly one face) and counts the holes
//! (connected loops of boundary edges) in num_groups. num_offending is the
//! number of boundary edges; examples are one vertex id per hole.
//! \throw InvalidMeshError when a face index is out of range (run
//!        check_face_indices() first).
CheckResult check_boundary_edges(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace subfab
