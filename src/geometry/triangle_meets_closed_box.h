// SPDX-License-Identifier: GPL-3.0-or-later
//! \file triangle_meets_closed_box.h
//! Exact contact test between a triangle and a closed axis-aligned box
//! (touching the boundary counts), used to decide whether a piece of a split
//! box touches the surface (thesis Section 4.3.3). CGAL stays in the .cpp.
#pragma once

#include "subfab/geometry/height_box.h"
#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! Exact: does the closed triangle (a, b, c) meet the closed box? A
//! degenerate triangle is treated as the segment or point it spans.
bool triangle_meets_closed_box(const Vec3& a, const Vec3& b, const Vec3& c, const Box3& box);

}  // namespace subfab::detail
