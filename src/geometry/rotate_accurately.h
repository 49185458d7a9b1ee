// SPDX-License-Identifier: GPL-3.0-or-later
//! \file rotate_accurately.h
//! Private: matrix x vector in doubles, as accurate as if computed in twice
//! the working precision and rounded once (Ogita, Rump and Oishi's Dot2:
//! error-free products with fma and error-free sums). Used to map blocks
//! between the canonical, input and machine frames with one rounding per
//! coordinate instead of five. Deterministic (plain IEEE operations).
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! a . b for 3-vectors, with Dot2 accuracy: |error| <= eps |a.b| + 2e-32 |a||b|.
inline double dot_accurately(const double* a, const double* b, int stride_a) {
  double p = a[0] * b[0];
  double s = std::fma(a[0], b[0], -p);
  for (int k = 1; k < 3; ++k) {
    const double x = a[k * stride_a], y = b[k];
    const double h = x * y;
    const double r = std::fma(x, y, -h);
    const double sum = p + h;  // two-sum of p and h: sum + q == p + h exactly
    const double z = sum - p;
    const double q = (p - (sum - z)) + (h - z);
    p = sum;
    s += q + r;
  }
  return p + s;
}

//! m x v, each coordinate rounded once from an (almost) exact dot product.
inline Vec3 rotate_accurately(const Eigen::Matrix3d& m, const Vec3& v) {
  Vec3 out;
  // Eigen matrices are column-major: row r starts at m.data() + r with stride 3.
  for (int r = 0; r < 3; ++r) out[r] = dot_accurately(m.data() + r, v.data(), 3);
  return out;
}

}  // namespace subfab::detail
