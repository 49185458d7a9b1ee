// SPDX-License-Identifier: GPL-3.0-or-later
//! \file exact_normal_signs.h
//! Exact signs of the components of a triangle's normal (b - a) x (c - a).
//! Each component is the orientation of the triangle projected on a
//! coordinate plane, decided exactly (normal_component_sign(),
//! exact_determinant_signs.h), so the sign of n.d for an axis direction d is
//! never wrong.
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

//! Facing signs under an overhang allowance s = overhang_sine(deg) >= 0:
//! component k is -1 when the unit normal has n_k < -s, +1 when n_k > s and
//! 0 otherwise, so the face counts as facing +e_k iff its sign k is >= 0 and
//! -e_k iff it is <= 0. s = 0: exactly exact_normal_signs(). s > 0 compares
//! the double unit normal with s (a tolerance the user chose, not a validity
//! decision); a zero-area face keeps its exact signs.
std::array<std::int8_t, 3> facing_signs(const Vec3& a, const Vec3& b, const Vec3& c, double overhang_sine);

//! facing_signs() for every face of the mesh, in face order (parallel).
//! `allowed` (optional, one entry per face): bit k set makes component k 0,
//! so the face counts as facing both +e_k and -e_k (decompose --tolerance:
//! the undercut under the face is within the tolerance, see
//! tolerance_allowances()).
std::vector<std::array<std::int8_t, 3>> facing_signs(const Mesh& mesh, double overhang_sine,
                                                     const std::vector<std::uint8_t>* allowed = nullptr);

}  // namespace subfab::detail
