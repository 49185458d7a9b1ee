// SPDX-License-Identifier: GPL-3.0-or-later
#include "validate/box_separation.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "subfab/validate/validate_decomposition.h"
#include "support/block_test_shapes.h"

namespace subfab {
namespace {

using detail::box_separation_bound;
using detail::FramedBlock;

// A staircase contact: the L [0,2]^2 \ [1,2]^2 (x z in [0,1]) and the box
// [1,2]^2 x [0,1] in its corner meet on x = 1 and y = 1; no plane separates them.
const Mesh kCorner = test::box_solid({1, 1, 0}, {2, 2, 1});

TEST(BoxSeparation, StaircaseContactIsBoundedExactlyInTheInputFrame) {
  const Mesh l = test::l_solid();
  EXPECT_GT(overlap_volume_bound(kCorner, l, Eigen::Matrix3d::Identity()), 0.5);  // the slab bound cannot
  const FramedBlock a(kCorner, Eigen::Matrix3d::Identity()), b(l, Eigen::Matrix3d::Identity());
  EXPECT_LT(box_separation_bound(a, b), 1e-14);  // the L stays out of the box's bounding box
  EXPECT_TRUE(std::isinf(box_separation_bound(b, a)));  // the box enters the L's bounding box
}

TEST(BoxSeparation, OverlappingBlocksAreNotBounded) {
  const Mesh wide = test::box_solid({0.5, 0, 0}, {2, 1.5, 1});  // enters the corner box
  const FramedBlock a(kCorner, Eigen::Matrix3d::Identity()), b(wide, Eigen::Matrix3d::Identity());
  EXPECT_TRUE(std::isinf(box_separation_bound(a, b)));
  EXPECT_TRUE(std::isinf(box_separation_bound(b, a)));
  // A block containing the whole box has no face in it: the inside test catches it.
  const Mesh big = test::box_solid({0, 0, -1}, {3, 3, 2});
  const FramedBlock c(big, Eigen::Matrix3d::Identity());
  EXPECT_TRUE(std::isinf(box_separation_bound(a, c)));
}

TEST(BoxSeparation, RotatedStaircaseIsBoundedInItsFrame) {
  // The same pair rotated (each coordinate rounded once): in the input frame
  // the contact planes are skew; in the blocks' frame the bound is of the
  // order of the rounding.
  const Eigen::Matrix3d r =
      (Eigen::AngleAxisd(0.3, Vec3::UnitX()) * Eigen::AngleAxisd(0.7, Vec3::UnitZ())).toRotationMatrix();
  Mesh box = kCorner, l = test::l_solid();
  for (Mesh* m : {&box, &l})
    for (Vec3& v : m->vertices) v = r * v;
  const FramedBlock a(box, r.transpose()), b(l, r.transpose());
  const double bound = box_separation_bound(a, b);
  EXPECT_GT(bound, 0.0);
  EXPECT_LT(bound, 1e-11);
  // In the input frame it cannot bound them (the L's bounding box is skew).
  const FramedBlock ai(box, Eigen::Matrix3d::Identity()), bi(l, Eigen::Matrix3d::Identity());
  EXPECT_TRUE(std::isinf(box_separation_bound(ai, bi)));
}

}  // namespace
}  // namespace subfab
