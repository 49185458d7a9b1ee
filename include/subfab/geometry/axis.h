// SPDX-License-Identifier: GPL-3.0-or-later
//! \file axis.h
//! The six milling directions of the height-field decomposition (thesis
//! Section 4.2: blocks are restricted to the major axes, which is what makes
//! a valid decomposition always reachable, Appendix C).
//!
//! A milling direction d says where the tool comes from: a block milled
//! along d has a flat base facing -d and every other face has a normal n
//! with n.d >= 0 (it is visible from +infinity along d).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "subfab/mesh/mesh.h"

namespace subfab {

enum class Axis : std::uint8_t { PosX = 0, NegX = 1, PosY = 2, NegY = 3, PosZ = 4, NegZ = 5 };

inline constexpr std::array<Axis, 6> kAllAxes = {Axis::PosX, Axis::NegX, Axis::PosY,
                                                 Axis::NegY, Axis::PosZ, Axis::NegZ};

//! 0 for x, 1 for y, 2 for z.
constexpr int axis_dimension(Axis a) { return static_cast<int>(a) / 2; }
//! +1 or -1.
constexpr int axis_sign(Axis a) { return (static_cast<int>(a) % 2 == 0) ? 1 : -1; }
//! Index 0..5 (for arrays indexed by axis).
constexpr int axis_index(Axis a) { return static_cast<int>(a); }
//! The opposite direction.
constexpr Axis opposite(Axis a) { return static_cast<Axis>(static_cast<int>(a) ^ 1); }
//! Unit vector of the direction.
Vec3 axis_direction(Axis a);
//! "+x", "-x", "+y", "-y", "+z", "-z".
std::string_view axis_name(Axis a);
//! Inverse of axis_name (also accepts upper case); nullopt if not one of them.
std::optional<Axis> parse_axis(std::string_view name);
//! The axis d maximising n.d (the seed axis of a triangle with normal n,
//! thesis Section 4.3.2); ties go to the first axis in kAllAxes order.
Axis closest_axis(const Vec3& n);

//! Largest overhang allowance accepted (degrees past vertical); see overhang_sine().
inline constexpr double kMaxOverhangAllowanceDeg = 45.0;

//! Sine of an overhang allowance (the `--max-overhang` option, default 0). A
//! face whose unit normal n has n.d >= -overhang_sine(deg) counts as facing
//! the milling direction d: it may lean up to `deg` degrees past vertical,
//! which a 3-axis machine cannot cut (it leaves material under it; the
//! thesis's blocks have such overhangs, up to 43 deg, reference notes).
//! 0 gives exactly 0: exact height fields, decided with exact predicates.
//! 	hrow InvalidArgumentError unless 0 <= deg <= kMaxOverhangAllowanceDeg.
double overhang_sine(double max_overhang_deg);

}  // namespace subfab
