// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_non_manifold_vertices.h"

#include <gtest/gtest.h>

#include "support/test_shapes.h"
#include "subfab/checks/check_boundary_edges.h"
#include "subfab/checks/check_non_manifold_edges.h"

namespace subfab {
namespace {

TEST(CheckNonManifoldVertices, ManifoldShapesPass) {
  EXPECT_TRUE(check_non_manifold_vertices(test::cube()).passed());
  EXPECT_TRUE(check_non_manifold_vertices(test::torus()).passed());
}

TEST(CheckNonManifoldVertices, TwoCubesSharingACornerPinchIt) {
  Mesh m = test::append(test::cube(), test::cube(Vec3(1, 1, 1)));
  ASSERT_EQ(weld_identical_vertices(m), 1u);  // corner (1, 1, 1) = vertex 7
  EXPECT_TRUE(check_non_manifold_edges(m).passed());
  EXPECT_TRUE(check_boundary_edges(m).passed());
  const CheckResult r = check_non_manifold_vertices(m);
  EXPECT_TRUE(r.failed());
  EXPECT_EQ(r.num_offending, 1u);
  EXPECT_EQ(r.examples, (std::vector<int>{7}));
  EXPECT_NE(r.message.find("e.g. vertex 7"), std::string::npos) << r.message;
}

TEST(CheckNonManifoldVertices, BowTieOfTwoOpenTriangles) {
  Mesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0)};
  m.faces = {{0, 1, 2}, {0, 3, 4}};
  const CheckResult r = check_non_manifold_vertices(m);
  EXPECT_EQ(r.examples, (std::vector<int>{0}));
}

TEST(CheckNonManifoldVertices, OpenFanIsNotPinched) {
  Mesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_TRUE(check_non_manifold_vertices(m).passed());
}

}  // namespace
}  // namespace subfab
