// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_components.h
//! Input check (informational): number of connected pieces.
#pragma once

#include "subfab/checks/check_result.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Counts the connected components (faces linked through shared vertices)
//! in num_groups. Always passes: several components are allowed, the message
//! reports them. Examples are the first face id of each component.
//! \throw InvalidMeshError when a face index is out of range (run
//!        check_face_indices() first).
CheckResult check_components(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace subfab
