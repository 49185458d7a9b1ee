// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mesh/float32.h"

#include <gtest/gtest.h>

#include <vector>

namespace subfab {
namespace {

TEST(Float32, EveryCoordinateOfAVec3IsRounded) {
  // Regression: Vec3(static_cast<float>(v.x()), ...) and
  // v.cast<float>().cast<double>() in a loop kept x and y unrounded under
  // GCC 12.2 -O3 (couplingdown.off, block 053's vertex x = 0x1.9677922ba4961p-2).
  std::vector<Vec3> points(5, Vec3(0x1.9677922ba4961p-2, 0x1.9677922ba4961p-2, 0x1.9677922ba4961p-2));
  for (Vec3& p : points) p = round_to_float32(p);
  for (const Vec3& p : points)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(p[k], 0x1.967792p-2) << "coordinate " << k;
}

TEST(Float32, RoundsToNearestAndKeepsFloats) {
  EXPECT_EQ(round_to_float32(1.0 + 0x1p-25), 1.0);             // below half a spacing (2^-23): down
  EXPECT_EQ(round_to_float32(1.0 + 0x1p-23 - 0x1p-26), 1.0 + 0x1p-23);  // above half: up
  EXPECT_EQ(round_to_float32(0.5f), 0.5);
  EXPECT_EQ(round_to_float32(-0x1.967792p-2), -0x1.967792p-2);
}

}  // namespace
}  // namespace subfab
