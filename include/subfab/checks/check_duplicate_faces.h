// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_duplicate_faces.h
//! Input check: no two faces use the same three vertices.
#pragma once

#include "subfab/checks/check_result.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Finds faces whose vertex set equals that of an earlier face (in either
//! orientation). num_offending counts the extra copies; examples are their
//! face ids.
CheckResult check_duplicate_faces(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace subfab
