// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_non_manifold_edges.h"

#include <gtest/gtest.h>

#include "support/test_shapes.h"
#include "subfab/checks/check_non_manifold_vertices.h"

namespace subfab {
namespace {

TEST(CheckNonManifoldEdges, CubePasses) {
  EXPECT_TRUE(check_non_manifold_edges(test::cube()).passed());
}

TEST(CheckNonManifoldEdges, ThreeTrianglesOnOneEdge) {
  Mesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, -1, 0)};
  m.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const CheckResult r = check_non_manifold_edges(m);
  EXPECT_TRUE(r.failed());
  EXPECT_EQ(r.num_offending, 1u);
  EXPECT_EQ(r.examples, (std::vector<int>{0}));
  EXPECT_NE(r.message.find("edge 0-1 (faces 0, 1 and 2)"), std::string::npos) << r.message;
}

TEST(CheckNonManifoldEdges, TwoCubesSharingAnEdge) {
  // Second cube shifted by (1, 1, 0): shares the edge x = y = 1 (vertices 3 and 7).
  Mesh m = test::append(test::cube(), test::cube(Vec3(1, 1, 0)));
  weld_identical_vertices(m);
  const CheckResult r = check_non_manifold_edges(m);
  EXPECT_EQ(r.num_offending, 1u);
  EXPECT_EQ(r.examples, (std::vector<int>{3}));
  // The edge's end vertices are not pinched: their faces connect through the edge.
  EXPECT_TRUE(check_non_manifold_vertices(m).passed());
}

}  // namespace
}  // namespace subfab
