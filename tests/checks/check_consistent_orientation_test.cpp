// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_consistent_orientation.h"

#include <gtest/gtest.h>

#include "support/test_shapes.h"

namespace subfab {
namespace {

TEST(CheckConsistentOrientation, OutwardAndInwardShapesAreConsistent) {
  EXPECT_TRUE(check_consistent_orientation(test::cube()).passed());
  EXPECT_TRUE(check_consistent_orientation(test::flipped(test::cube())).passed());
  EXPECT_TRUE(check_consistent_orientation(test::torus()).passed());
}

TEST(CheckConsistentOrientation, OneFlippedFaceIsFound) {
  Mesh m = test::cube();
  std::swap(m.faces[5][1], m.faces[5][2]);
  const CheckResult r = check_consistent_orientation(m);
  EXPECT_TRUE(r.failed());
  EXPECT_EQ(r.num_offending, 3u);  // its three edges
  EXPECT_EQ(r.examples, (std::vector<int>{5}));
  EXPECT_NE(r.message.find("1 face disagrees with its neighbours, e.g. face 5"), std::string::npos)
      << r.message;
}

TEST(CheckConsistentOrientation, MinorityIsReportedWhateverTheSeed) {
  Mesh m = test::cube();
  // Flip the 8 side faces: the 4 faces of the top and bottom are now the minority.
  for (std::size_t f = 4; f < 12; ++f) std::swap(m.faces[f][1], m.faces[f][2]);
  const CheckResult r = check_consistent_orientation(m);
  EXPECT_EQ(r.examples, (std::vector<int>{0, 1, 2, 3}));
}

TEST(CheckConsistentOrientation, BalancedNonManifoldEdgeIsConsistent) {
  // Two outward cubes sharing an edge: it is used twice in each direction.
  Mesh m = test::append(test::cube(), test::cube(Vec3(1, 1, 0)));
  weld_identical_vertices(m);
  EXPECT_TRUE(check_consistent_orientation(m).passed());
}

}  // namespace
}  // namespace subfab
