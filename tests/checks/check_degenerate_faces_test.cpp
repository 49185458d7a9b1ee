// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_degenerate_faces.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/test_shapes.h"

namespace subfab {
namespace {

TEST(CheckDegenerateFaces, CubeAndTetrahedronPass) {
  EXPECT_TRUE(check_degenerate_faces(test::cube()).passed());
  EXPECT_TRUE(check_degenerate_faces(test::tetrahedron()).passed());
}

TEST(CheckDegenerateFaces, RepeatedIndexAndCollinearCornersReported) {
  Mesh m = test::cube();
  m.faces.push_back({0, 1, 1});  // face 12: repeated vertex
  m.vertices.push_back(Vec3(0.5, 0, 0));
  m.faces.push_back({0, 8, 1});  // face 13: corners on one line
  const CheckResult r = check_degenerate_faces(m);
  EXPECT_TRUE(r.failed());
  EXPECT_EQ(r.num_offending, 2u);
  EXPECT_EQ(r.examples, (std::vector<int>{12, 13}));
  EXPECT_NE(r.message.find("1 with a repeated vertex, 1 with collinear corners"), std::string::npos)
      << r.message;
}

TEST(CheckDegenerateFaces, DecidedExactlyWithoutTolerance) {
  Mesh m;
  // Exactly collinear (every coordinate doubles exactly)...
  m.vertices = {Vec3(0, 0, 0), Vec3(0.1, 0.2, 0.3), Vec3(0.2, 0.4, 0.6),
                // ...and a sliver whose area is tiny but not zero.
                Vec3(1, 1, 1), Vec3(2, 2, 2), Vec3(3, 3, 3 + std::ldexp(1.0, -50))};
  m.faces = {{0, 1, 2}, {3, 4, 5}};
  const CheckResult r = check_degenerate_faces(m);
  EXPECT_EQ(r.num_offending, 1u);
  EXPECT_EQ(r.examples, (std::vector<int>{0}));
}

TEST(CheckDegenerateFaces, SkipsFacesItCannotExamine) {
  Mesh m = test::cube();
  m.faces[0][0] = 99;
  m.vertices[7].x() = std::nan("");
  EXPECT_NO_THROW(check_degenerate_faces(m));
}

}  // namespace
}  // namespace subfab
