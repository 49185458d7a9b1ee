// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/geometry/coordinate_rounding.h"

#include <gtest/gtest.h>

#include <cmath>

namespace subfab {
namespace {

Mesh points(std::vector<Vec3> v) {
  Mesh m;
  m.vertices = std::move(v);
  return m;
}

TEST(CoordinateRounding, SixDigitsBelowOneAreHalfAMillionth) {
  // "%g" output of a unit-sized model: 6 significant digits, largest 0.886405.
  const Mesh m = points({Vec3(0.831738, -0.0626717, 0.5), Vec3(-0.886405, 0.203766, -0.110284)});
  EXPECT_DOUBLE_EQ(coordinate_rounding(m), 0.5e-6);
}

TEST(CoordinateRounding, ScalesWithTheLargestCoordinate) {
  // 6 digits, largest 87.9425 (two digits before the point): +-5e-5.
  const Mesh m = points({Vec3(5.47789, 31.1822, 10.7274), Vec3(87.9425, -10.5744, -19.6009)});
  EXPECT_DOUBLE_EQ(coordinate_rounding(m), 0.5e-4);
  // One more digit anywhere makes the whole file 7 digits.
  Mesh finer = m;
  finer.vertices.push_back(Vec3(1.234567, 0, 0));
  EXPECT_DOUBLE_EQ(coordinate_rounding(finer), 0.5e-5);
}

TEST(CoordinateRounding, Float32IsHalfAnUlpAtTheLargest) {
  // float literals (a cast of a double constant may be folded away under -frounding-math)
  const float third = 1.0f / 3.0f;
  const Mesh m = points({Vec3(0.1f, -0.7f, third), Vec3(0.3f, 0.0f, 0.2f)});
  // largest |x| = 0.7f, in [0.5, 1): 2^-24 bounds the float32 rounding there.
  EXPECT_DOUBLE_EQ(coordinate_rounding(m), std::ldexp(1.0, -24));
}

TEST(CoordinateRounding, FullDoublePrecisionIsZero) {
  EXPECT_EQ(coordinate_rounding(points({Vec3(1.0 / 3.0, 0.1, -2.0 / 7.0)})), 0.0);
  EXPECT_EQ(coordinate_rounding(Mesh{}), 0.0);
  EXPECT_EQ(coordinate_rounding(points({Vec3(0, 0, 0)})), 0.0);
}

}  // namespace
}  // namespace subfab
