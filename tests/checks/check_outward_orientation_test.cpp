// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_outward_orientation.h"

#include <gtest/gtest.h>

#include "support/test_shapes.h"
#include "subfab/core/error.h"

namespace subfab {
namespace {

TEST(CheckOutwardOrientation, OutwardShapesPass) {
  EXPECT_TRUE(check_outward_orientation(test::cube()).passed());
  EXPECT_TRUE(check_outward_orientation(test::tetrahedron()).passed());
  EXPECT_TRUE(check_outward_orientation(test::torus()).passed());
}

TEST(CheckOutwardOrientation, InwardCubeFails) {
  const CheckResult r = check_outward_orientation(test::flipped(test::cube()));
  EXPECT_TRUE(r.failed());
  EXPECT_EQ(r.num_offending, 12u);
  EXPECT_NE(r.message.find("oriented inward"), std::string::npos) << r.message;
}

TEST(CheckOutwardOrientation, CavityInsideASolidIsFine) {
  // Outer cube outward, inner cube inward: a hollow solid, positive volume.
  const Mesh m = test::append(test::cube(Vec3::Zero(), 3.0),
                              test::flipped(test::cube(Vec3(1, 1, 1), 1.0)));
  EXPECT_TRUE(check_outward_orientation(m).passed());
}

TEST(CheckOutwardOrientation, SeparateInsideOutPartIsFound) {
  // A big outward cube and, beside it, a small inward one: positive in total.
  const Mesh m = test::append(test::cube(Vec3::Zero(), 3.0),
                              test::flipped(test::cube(Vec3(5, 0, 0), 1.0)));
  const CheckResult r = check_outward_orientation(m);
  EXPECT_TRUE(r.failed());
  EXPECT_EQ(r.num_offending, 12u);
  EXPECT_EQ(r.examples, (std::vector<int>{12}));
  EXPECT_NE(r.message.find("1 component is oriented inward"), std::string::npos) << r.message;
}

TEST(CheckOutwardOrientation, ZeroVolumeIsDecidedExactly) {
  // A cube and the same cube inward, far from the origin: the volumes cancel exactly.
  const Vec3 far(1e8 + 0.1, -3e7, 12345.678);
  const Mesh m = test::append(test::cube(far, 0.3), test::flipped(test::cube(far, 0.3)));
  const CheckResult r = check_outward_orientation(m);
  EXPECT_TRUE(r.failed());
  EXPECT_EQ(r.num_offending, 0u);
  EXPECT_NE(r.message.find("no volume"), std::string::npos) << r.message;
}

TEST(CheckOutwardOrientation, TinyFarAwaySolidKeepsItsSign) {
  const Mesh m = test::cube(Vec3(1e9, 1e9, 1e9), 1e-3);
  EXPECT_TRUE(check_outward_orientation(m).passed());
  EXPECT_TRUE(check_outward_orientation(test::flipped(m)).failed());
}

TEST(CheckOutwardOrientation, RefusesNonFiniteCoordinates) {
  Mesh m = test::cube();
  m.vertices[0].x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(check_outward_orientation(m), InvalidMeshError);
}

}  // namespace
}  // namespace subfab
