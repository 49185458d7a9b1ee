// SPDX-License-Identifier: GPL-3.0-or-later
//! \file float32.h
//! Rounding to float32, as binary STL and float PLY store coordinates.
#pragma once

#include "subfab/mesh/mesh.h"

namespace subfab {

//! x rounded to the nearest float32, as a double. Through a volatile: GCC 12.2
//! at -O2/-O3 (its SLP vectorizer) drops the double -> float -> double pair
//! when the three coordinates of a Vec3 are rounded together
//! (`Vec3(static_cast<float>(v.x()), ...)` or `v.cast<float>().cast<double>()`
//! returned x and y unrounded, z rounded), which made the float32 check of
//! the export pass meshes that are not solids once written (couplingdown.off
//! at --tolerance 1e-3, block 053).
inline double round_to_float32(double x) {
  volatile float f = static_cast<float>(x);
  return static_cast<double>(f);
}

//! v with every coordinate rounded to float32 (round_to_float32()).
inline Vec3 round_to_float32(const Vec3& v) {
  return Vec3(round_to_float32(v.x()), round_to_float32(v.y()), round_to_float32(v.z()));
}

}  // namespace subfab
