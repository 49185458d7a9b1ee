// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/geometry/axis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "subfab/core/error.h"

namespace subfab {
namespace {

TEST(Axis, NamesRoundTrip) {
  for (Axis a : kAllAxes) {
    auto parsed = parse_axis(axis_name(a));
    ASSERT_TRUE(parsed.has_value());
    EXPECT_EQ(*parsed, a);
  }
  EXPECT_EQ(parse_axis("-Z"), Axis::NegZ);
  EXPECT_FALSE(parse_axis("z").has_value());
  EXPECT_FALSE(parse_axis("+w").has_value());
  EXPECT_FALSE(parse_axis("*x").has_value());
}

TEST(Axis, DirectionsAreUnitAndOpposite) {
  for (Axis a : kAllAxes) {
    EXPECT_DOUBLE_EQ(axis_direction(a).norm(), 1.0);
    EXPECT_EQ(axis_direction(opposite(a)), -axis_direction(a));
    EXPECT_NE(opposite(a), a);
  }
}

TEST(Axis, ClosestAxisPicksLargestComponent) {
  EXPECT_EQ(closest_axis(Vec3(0.1, -0.9, 0.3)), Axis::NegY);
  EXPECT_EQ(closest_axis(Vec3(0.0, 0.0, 1.0)), Axis::PosZ);
  EXPECT_EQ(closest_axis(Vec3(-0.7, 0.5, 0.5)), Axis::NegX);
  // A tie goes to the first axis in kAllAxes order.
  EXPECT_EQ(closest_axis(Vec3(1, 1, 0).normalized()), Axis::PosX);
}

TEST(Axis, OverhangSineIsExactlyZeroByDefaultAndRejectsBadAngles) {
  EXPECT_EQ(overhang_sine(0.0), 0.0);
  EXPECT_NEAR(overhang_sine(30.0), 0.5, 1e-15);
  EXPECT_NEAR(overhang_sine(kMaxOverhangAllowanceDeg), std::sqrt(0.5), 1e-15);
  for (double bad : {-0.5, 45.5, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_THROW(overhang_sine(bad), InvalidArgumentError) << bad;
}

}  // namespace
}  // namespace subfab
