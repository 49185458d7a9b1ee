// SPDX-License-Identifier: GPL-3.0-or-later
//! \file lattice_directions.h
//! The 26 directions {-1, 0, 1}^3 minus 0 (thesis Section 3.2): every facet
//! of the marching-cubes surface of Chapter 3 has its normal along one of
//! them, which is what bounds the fold angles a V-bit has to cut.
#pragma once

#include <array>
#include <optional>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! The 26 integer directions, in lexicographic order of (x, y, z).
const std::array<std::array<int, 3>, 26>& lattice_directions();

//! Index (into lattice_directions()) of the direction that `normal` is
//! parallel to, within `angle_tolerance` radians; nullopt if none.
std::optional<int> lattice_direction_index(const Vec3& normal, double angle_tolerance = 1e-9);

}  // namespace subfab
