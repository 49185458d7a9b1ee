// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/axis.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace subfab
