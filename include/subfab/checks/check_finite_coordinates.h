// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_finite_coordinates.h
//! Input check: every vertex coordinate is a finite number.
#pragma once

#include "subfab/checks/check_result.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Checks that no vertex has a NaN or infinite coordinate (all vertices,
//! referenced or not). Examples are vertex ids. Input validation (issue 2,
//! item 5); no thesis section.
CheckResult check_finite_coordinates(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace subfab
