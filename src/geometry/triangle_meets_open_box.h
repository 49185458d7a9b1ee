// SPDX-License-Identifier: GPL-3.0-or-later
//! \file triangle_meets_open_box.h
//! Exact contact test between a triangle and the open interior of an
//! axis-aligned box (touching the boundary does not count): the test behind
//! the validity of height-field boxes (thesis Section 4.3.2: no triangle
//! facing away from the milling direction may enter a box). Its closed-box
//! counterpart is triangle_meets_closed_box.h.
#pragma once

#include "subfab/geometry/height_box.h"
#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! Exact: does the closed triangle (a, b, c) meet the open interior of `box`?
//! (Separating-axis test with weak separation over the 13 candidate axes,
//! every sign decided exactly.) False when the box has a zero extent.
bool triangle_meets_open_box(const Vec3& a, const Vec3& b, const Vec3& c, const Box3& box);

}  // namespace subfab::detail
