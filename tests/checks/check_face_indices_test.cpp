// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_face_indices.h"

#include <gtest/gtest.h>

#include "support/test_shapes.h"
#include "subfab/checks/check_boundary_edges.h"
#include "subfab/checks/check_self_intersections.h"
#include "subfab/core/error.h"

namespace subfab {
namespace {

TEST(CheckFaceIndices, CubePasses) { EXPECT_TRUE(check_face_indices(test::cube()).passed()); }

TEST(CheckFaceIndices, NegativeAndTooLargeIndicesReported) {
  Mesh m = test::cube();
  m.faces[2][1] = 8;   // one past the end
  m.faces[7][0] = -1;  // negative
  const CheckResult r = check_face_indices(m);
  EXPECT_TRUE(r.failed());
  EXPECT_EQ(r.num_offending, 2u);
  EXPECT_EQ(r.examples, (std::vector<int>{2, 7}));
  EXPECT_NE(r.message.find("face 2 uses vertex 8"), std::string::npos) << r.message;
}

TEST(CheckFaceIndices, OtherChecksRefuseBadIndicesInsteadOfCrashing) {
  Mesh m = test::cube();
  m.faces[0][0] = 1000;
  EXPECT_THROW(check_boundary_edges(m), InvalidMeshError);
  EXPECT_THROW(check_self_intersections(m), InvalidMeshError);
}

}  // namespace
}  // namespace subfab
