// SPDX-License-Identifier: GPL-3.0-or-later
//! \file exact_normal_signs.h
//! Exact signs of the components of a triangle's normal (b - a) x (c - a).
//! Each component is the orientation of the triangle projected on a
//! coordinate plane, decided with exact predicates (CGAL Epick), so the sign
//! of n.d for an axis direction d is never wrong.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! Signs (-1, 0, +1) of the x, y and z components of (b - a) x (c - a), exact.
std::array<std::int8_t, 3> exact_normal_signs(const Vec3& a, const Vec3& b, const Vec3& c);

//! Exact signs for every face of the mesh, in face order (parallel).
std::vector<std::array<std::int8_t, 3>> exact_normal_signs(const Mesh& mesh);

}  // namespace subfab::detail
