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

TEST(CheckSinglePrecision, FrustumTopVertexRoundedOntoItsBase) {
  // Regression (kitten --max-height 0.05, block 040 self-intersected after
  // float32 rounding), minimal mesh: a frustum 1e-7 tall over z = 1 whose
  // top corners round up (1 + 1.19e-7) but one rounds down onto the base
  // plane, touching the base face: no vertex welds, the faces intersect.
  Mesh m;
  m.vertices = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1},
                {0.25, 0.25, 1 + 1e-7}, {0.75, 0.25, 1 + 1e-7}, {0.75, 0.75, 1 + 1e-7}, {0.25, 0.75, 1 + 2e-8}};
  m.faces = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}};
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    m.faces.push_back({i, j, 4 + j});
    m.faces.push_back({i, 4 + j, 4 + i});
  }
  ASSERT_TRUE(check_closed_solid(m).ok());
  const SinglePrecisionReport r = check_single_precision(m);
  EXPECT_EQ(r.num_welded, 0u);
  EXPECT_GT(r.num_self_intersections, 0u);
  EXPECT_FALSE(r.ok());
}

}  // namespace
}  // namespace subfab
