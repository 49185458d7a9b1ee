// SPDX-License-Identifier: GPL-3.0-or-later
//! \file validate_booleans.h
//! Private: variants of the exact booleans of validate_booleans.cpp for the
//! milled-shape measures, which report volumes to the last digit and must
//! not depend on the thread count.
#pragma once

#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! blocks_overlap() with the result's volume evaluated exactly (then
//! rounded once), so independent of how the corefinement triangulated it
//! (which depends on heap addresses, hence on the thread that ran it).
double exact_blocks_overlap(const Mesh& a, const Mesh& b);

//! volume_outside() with the volume evaluated exactly, as exact_blocks_overlap().
double exact_volume_outside(const Mesh& block, const Mesh& solid);

}  // namespace subfab::detail
