// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_boundary_edges.h"

#include <gtest/gtest.h>

#include "support/test_shapes.h"

namespace subfab {
namespace {

TEST(CheckBoundaryEdges, ClosedShapesPass) {
  EXPECT_TRUE(check_boundary_edges(test::cube()).passed());
  EXPECT_TRUE(check_boundary_edges(test::tetrahedron()).passed());
  EXPECT_TRUE(check_boundary_edges(test::torus()).passed());
}

TEST(CheckBoundaryEdges, CubeWithoutOneSideHasOneHoleOfFourEdges) {
  Mesh m = test::cube();
  m.faces.erase(m.faces.begin(), m.faces.begin() + 2);  // the z = 0 side
  const CheckResult r = check_boundary_edges(m);
  EXPECT_TRUE(r.failed());
  EXPECT_EQ(r.num_offending, 4u);
  EXPECT_EQ(r.num_groups, 1u);
  EXPECT_EQ(r.element, CheckElement::Vertex);
  EXPECT_EQ(r.examples, (std::vector<int>{0}));
  EXPECT_EQ(r.message,
            "the mesh is not closed: 4 boundary edges in 1 hole, e.g. around vertex 0; close the "
            "holes before decomposing");
}

TEST(CheckBoundaryEdges, OpenTubeHasTwoHoles) {
  Mesh m = test::cube();
  m.faces.erase(m.faces.begin(), m.faces.begin() + 4);  // z = 0 and z = 1 sides
  const CheckResult r = check_boundary_edges(m);
  EXPECT_EQ(r.num_offending, 8u);
  EXPECT_EQ(r.num_groups, 2u);
  EXPECT_EQ(r.examples, (std::vector<int>{0, 4}));
}

TEST(CheckBoundaryEdges, SingleTriangleIsOneHole) {
  Mesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  m.faces = {{0, 1, 2}};
  const CheckResult r = check_boundary_edges(m);
  EXPECT_EQ(r.num_offending, 3u);
  EXPECT_EQ(r.num_groups, 1u);
}

}  // namespace
}  // namespace subfab
