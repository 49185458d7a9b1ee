// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_duplicate_faces.h"

#include <gtest/gtest.h>

#include "support/test_shapes.h"

namespace subfab {
namespace {

TEST(CheckDuplicateFaces, CubePasses) { EXPECT_TRUE(check_duplicate_faces(test::cube()).passed()); }

TEST(CheckDuplicateFaces, SameVertexSetInEitherOrientationReported) {
  Mesh m = test::cube();
  m.faces.push_back({3, 2, 0});  // face 12: face 0 reversed
  m.faces.push_back({7, 4, 5});  // face 13: face 2 rotated
  const CheckResult r = check_duplicate_faces(m);
  EXPECT_TRUE(r.failed());
  EXPECT_EQ(r.num_offending, 2u);
  EXPECT_EQ(r.examples, (std::vector<int>{12, 13}));
  EXPECT_NE(r.message.find("face 12 (same as face 0)"), std::string::npos) << r.message;
}

TEST(CheckDuplicateFaces, ThreeCopiesCountTwoExtras) {
  Mesh m = test::tetrahedron();
  m.faces.push_back(m.faces[1]);
  m.faces.push_back(m.faces[1]);
  EXPECT_EQ(check_duplicate_faces(m).num_offending, 2u);
}

}  // namespace
}  // namespace subfab
