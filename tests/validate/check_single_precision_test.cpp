// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/validate/check_single_precision.h"

#include <gtest/gtest.h>

#include "support/block_test_shapes.h"

namespace subfab {
namespace {

using test::box_solid;

TEST(CheckSinglePrecision, BoxPasses) {
  const SinglePrecisionReport r = check_single_precision(box_solid({0.1, 0.2, 1.0}, {4.3, 2.4, 1.001}));
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.num_welded, 0u);
}

TEST(CheckSinglePrecision, SheetCollapses) {
  // Issue 17: a 4.3 x 2.4 x 1.3e-7 sheet at z = 1; float32's spacing there
  // is 1.2e-7, so its top and bottom round to the same plane and weld.
  const SinglePrecisionReport r = check_single_precision(box_solid({0, 0, 1.0}, {4.3, 2.4, 1.0 + 4e-8}));
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.num_welded, 4u);
}

TEST(CheckSinglePrecision, SheetThinAlongXOrYCollapsesToo) {
  // Regression: GCC 12.2 -O3 vectorized the rounding of the three
  // coordinates and dropped it for x and y (only z was rounded), so a sheet
  // thin along x or y passed (couplingdown.off at --tolerance 1e-3: block
  // 053's STL was not a solid, decompose's check said it was).
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 lo(0, 0, 0), hi(4.3, 2.4, 3.1);
    lo[axis] = 1.0;
    hi[axis] = 1.0 + 4e-8;
    const SinglePrecisionReport r = check_single_precision(box_solid(lo, hi));
    EXPECT_FALSE(r.ok()) << "axis " << axis;
    EXPECT_EQ(r.num_welded, 4u) << "axis " << axis;
  }
}

TEST(CheckSinglePrecision, FrustumTopVertexRoundedOntoItsBase) {
  // Regression (kitten --max-height 0.05, block 040 self-intersected after
  // float32 rounding): see test::float32_frustum().
  const Mesh m = test::float32_frustum();
  ASSERT_TRUE(check_closed_solid(m).ok());
  const SinglePrecisionReport r = check_single_precision(m);
  EXPECT_EQ(r.num_welded, 0u);
  EXPECT_GT(r.num_self_intersections, 0u);
  EXPECT_FALSE(r.ok());
}

}  // namespace
}  // namespace subfab
