// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_face_indices.h
//! Input check: every face refers to existing vertices.
#pragma once

#include "subfab/checks/check_result.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Checks that every face index lies in [0, #V). The readers already refuse
//! such files; this guards meshes built in code. Examples are face ids.
CheckResult check_face_indices(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace subfab
