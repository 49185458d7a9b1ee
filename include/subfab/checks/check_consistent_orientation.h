// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_consistent_orientation.h
//! Input check: neighbouring faces agree on their orientation.
#pragma once

#include "subfab/checks/check_result.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Finds edges whose two directions are not used equally often by their
//! faces (for a manifold edge: both faces traverse it in the same
//! direction). num_offending counts such edges; examples are the faces that
//! disagree with the majority of their connected piece (face ids).
//! \throw InvalidMeshError when a face index is out of range (run
//!        check_face_indices() first).
CheckResult check_consistent_orientation(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace subfab
