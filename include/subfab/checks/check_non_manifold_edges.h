// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_non_manifold_edges.h
//! Input check: no edge is shared by more than two faces.
#pragma once

#include "subfab/checks/check_result.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Finds edges shared by three faces or more. num_offending counts such
//! edges; examples are the smaller vertex id of each (the message names the
//! whole edge and its faces).
//! \throw InvalidMeshError when a face index is out of range (run
//!        check_face_indices() first).
CheckResult check_non_manifold_edges(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace subfab
