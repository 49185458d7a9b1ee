// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_outward_orientation.h
//! Input check: a closed mesh encloses positive volume.
#pragma once

#include "subfab/checks/check_result.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Checks that the signed volume is positive, i.e. that the faces point out
//! of the solid; the sign is decided exactly (floating-point sum with an
//! error bound, exact rational sum when that bound is not conclusive).
//! Only meaningful for a closed, consistently oriented mesh.
//! Failed when the total volume is negative (num_offending = #F, no
//! examples: flipping every face fixes it), zero (num_offending = 0), or when
//! a connected component has negative volume and its bounding box is not
//! inside that of a positive component, so it cannot be a cavity
//! (num_offending = faces of such components; examples = their first faces).
//! \throw InvalidMeshError when an index is out of range or a coordinate is
//!        not finite (run those checks first).
CheckResult check_outward_orientation(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace subfab
