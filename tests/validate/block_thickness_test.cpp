// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/validate/block_thickness.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "support/block_test_shapes.h"

namespace subfab {
namespace {

using test::box_solid;
using test::l_solid;

TEST(BlockThickness, BoxIsItsSmallestSide) {
  const BlockThickness t = block_thickness(box_solid({1, 2, 3}, {4, 2.5, 5}));  // 3 x 0.5 x 2
  EXPECT_NEAR(t.along[0], 3.0, 1e-12);
  EXPECT_NEAR(t.along[1], 0.5, 1e-12);
  EXPECT_NEAR(t.along[2], 2.0, 1e-12);
  EXPECT_NEAR(t.thickness, 0.5, 1e-12);
  EXPECT_EQ(t.thinnest_row, 1);
  EXPECT_NEAR(t.axis.y(), 1.0, 1e-15);
}

TEST(BlockThickness, ThinPlateIsItsThickness) {
  // A 4.3 x 2.4 plate 1.3e-4 thick (the shape of issue 17's sheet, thicker).
  const BlockThickness t = block_thickness(box_solid({0, 0, 0}, {4.3, 2.4, 1.3e-4}));
  EXPECT_NEAR(t.thickness, 1.3e-4, 1e-12);
  EXPECT_EQ(t.thinnest_row, 2);
}

TEST(BlockThickness, LShapeAlongZIsItsHeight) {
  // A prism along z: every vertical line through it has one chord of length 1.
  EXPECT_NEAR(block_thickness(l_solid()).along[2], 1.0, 1e-12);
  // Along x: volume 3, projected area with multiplicity 2 (y in [0,1] length 2, [1,2] length 1; area 2).
  EXPECT_NEAR(block_thickness(l_solid()).along[0], 1.5, 1e-12);
}

TEST(BlockThickness, MeasuredInTheBlocksFrame) {
  // The same plate rotated 30 degrees about x: in the input frame its
  // extents are not its thickness, in its own frame they are.
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.5235987755982988, Vec3::UnitX()).toRotationMatrix();
  Mesh plate = box_solid({0, 0, 0}, {2, 1, 0.01});
  for (Vec3& v : plate.vertices) v = r * v;
  EXPECT_GT(block_thickness(plate).thickness, 0.011);
  EXPECT_NEAR(block_thickness(plate, r.transpose()).thickness, 0.01, 1e-12);
}

TEST(BlockThickness, InsideOutMeshHasNoThickness) {
  Mesh box = box_solid({0, 0, 0}, {1, 1, 1});
  for (Triangle& f : box.faces) std::swap(f[1], f[2]);
  EXPECT_EQ(block_thickness(box).thickness, 0.0);
}

}  // namespace
}  // namespace subfab
