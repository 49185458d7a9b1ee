// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_components.h"

#include <gtest/gtest.h>

#include "support/test_shapes.h"

namespace subfab {
namespace {

TEST(CheckComponents, OneCube) {
  const CheckResult r = check_components(test::cube());
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(r.num_groups, 1u);
  EXPECT_EQ(r.message, "1 connected component");
}

TEST(CheckComponents, TwoDisjointCubesAreAllowedAndReported) {
  const Mesh m = test::append(test::cube(), test::cube(Vec3(3, 0, 0)));
  const CheckResult r = check_components(m);
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(r.num_groups, 2u);
  EXPECT_EQ(r.examples, (std::vector<int>{0, 12}));
  EXPECT_NE(r.message.find("2 connected components (faces: 12 12)"), std::string::npos)
      << r.message;
}

TEST(CheckComponents, CubesSharingACornerAreOneComponent) {
  Mesh m = test::append(test::cube(), test::cube(Vec3(1, 1, 1)));
  weld_identical_vertices(m);
  EXPECT_EQ(check_components(m).num_groups, 1u);
}

}  // namespace
}  // namespace subfab
