// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/geometry/coordinate_rounding.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace subfab {

namespace {

//! Whether "%.<digits>g" of x reads back to x exactly.
bool round_trips(double x, int digits) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return std::strtod(buf, nullptr) == x;
}

}  // namespace

double coordinate_rounding(const Mesh& mesh) {
  double largest = 0;
  int digits = 1;  // the most significant digits any coordinate needs so far
  bool float32 = true;
  for (const Vec3& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      const double x = v[k];
      if (!std::isfinite(x)) return 0;
      largest = std::max(largest, std::abs(x));
      float32 = float32 && static_cast<double>(static_cast<float>(x)) == x;
      if (digits > 9) {  // past 9 digits only float32 matters
        if (!float32) return 0;  // full double precision
        continue;
      }
      if (x == 0) continue;
      while (digits <= 17 && !round_trips(x, digits)) ++digits;
      if (digits > 9 && !float32) return 0;
    }
  if (!(largest > 0)) return 0;
  if (digits <= 9) return 0.5 * std::pow(10.0, std::floor(std::log10(largest)) - digits + 1);
  if (float32) return std::ldexp(1.0, std::ilogb(largest) + 1 - 24);
  return 0;
}

}  // namespace subfab
