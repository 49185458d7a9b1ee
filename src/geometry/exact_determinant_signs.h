// SPDX-License-Identifier: GPL-3.0-or-later
//! \file exact_determinant_signs.h
//! Exact signs of the small determinants the exact box tests are made of
//! (thesis Sections 4.3.2-4.3.3: validity of height-field boxes, carving):
//! a 2x2 determinant of differences of doubles, a component of a triangle's
//! normal, and the 3D orientation of a point against a triangle's plane.
//! Each is evaluated in doubles with Shewchuk's error bound as a filter, and
//! with exact rationals when the filter cannot decide: the sign is never
//! wrong and depends only on the input doubles.
#pragma once

#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! Sign (-1, 0, +1) of a number (exact for the sign of a difference of
//! doubles: a - b rounds to zero only when a == b).
template <class T>
int sign_of_number(T x) {
  return (x > 0) - (x < 0);
}

//! Exact sign of (ux1 - ux0) * (vy1 - vy0) - (uy1 - uy0) * (vx1 - vx0).
int det2_sign(double ux1, double ux0, double uy1, double uy0, double vx1, double vx0, double vy1,
              double vy0);

//! Exact sign (-1, 0, +1) of component `dim` (0, 1, 2) of (b - a) x (c - a).
int normal_component_sign(const Vec3& a, const Vec3& b, const Vec3& c, int dim);

//! Exact sign of det[b - a, c - a, p - a] = ((b - a) x (c - a)).(p - a):
//! +1 when p is on the side the normal points to.
int orient3d_sign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p);

}  // namespace subfab::detail
