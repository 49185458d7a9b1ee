// SPDX-License-Identifier: GPL-3.0-or-later
//! \file facet_unit_normal.h
//! Private: the unit outward normal of a facet of a PolyMesh, used to lay
//! facets flat and to refold the nets (thesis Section 3.3.3).
#pragma once

#include "subfab/unfold/poly_mesh.h"

namespace subfab::unfold_detail {

//! Unit normal of facet f: its lattice direction when it has one (normal
//! index 0..25), otherwise its outer loop's normalised vector area (sum of
//! the cross products of consecutive corners).
Vec3 facet_unit_normal(const PolyMesh& mesh, int f);

}  // namespace subfab::unfold_detail
