// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_degenerate_faces.h
//! Input check: no face has zero area (decided exactly).
#pragma once

#include "subfab/checks/check_result.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Finds faces with a repeated vertex index or three exactly collinear
//! corners (CGAL exact orientation predicate, no tolerance). Examples are
//! face ids. Does not throw on bad input: faces with out-of-range indices
//! or non-finite corners are not examined (see check_face_indices(),
//! check_finite_coordinates()).
CheckResult check_degenerate_faces(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace subfab
