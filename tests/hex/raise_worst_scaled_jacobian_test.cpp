// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/raise_worst_scaled_jacobian.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "subfab/hex/scaled_jacobian.h"
#include "support/hex_test_shapes.h"
#include "support/test_shapes.h"

namespace subfab {
namespace {

double min_of(const std::vector<double>& q) { return *std::min_element(q.begin(), q.end()); }

//! Every boundary vertex of a grid in [0,n]^3 is on the cube's surface.
void expect_on_cube(const HexMesh& mesh, int n) {
  for (std::size_t w = 0; w < mesh.vertices.size(); ++w) {
    const Vec3& q = mesh.vertices[w];
    const double to_face = std::min({q.x(), n - q.x(), q.y(), n - q.y(), q.z(), n - q.z()});
    EXPECT_GT(to_face, -1e-12) << w;
  }
}

// An interior vertex dragged (its 8 hexahedra valid but down to ~.4): the
// patch around it is optimised jointly and the grid comes back (known
// answer: the unit grid, all 1), the minimum never drops, and hexahedra far
// from the patch do not move.
TEST(RaiseWorstScaledJacobian, DraggedInteriorVertexComesBack) {
  test::GridInCube g(6);
  const std::size_t v = g.id(2, 2, 2);
  g.mesh.vertices[v] = Vec3(2.35, 2.3, 1.7);
  const std::vector<double> before = scaled_jacobians(g.mesh);
  ASSERT_GT(min_of(before), 0.0);
  ASSERT_LT(min_of(before), 0.5);
  const RaiseWorstScaledJacobianReport r = raise_worst_scaled_jacobian(g.mesh, g.surface);
  const std::vector<double> after = scaled_jacobians(g.mesh);
  EXPECT_DOUBLE_EQ(r.min_before, min_of(before));
  EXPECT_DOUBLE_EQ(r.min_after, min_of(after));
  EXPECT_GT(r.targets_before, 0u);
  EXPECT_EQ(r.targets_after, 0u);
  EXPECT_GT(min_of(after), 0.9);
  EXPECT_GT(r.steps, 0u);
  // the far corner is outside every patch (a hexahedron at v grown by 2 rings)
  EXPECT_EQ(g.mesh.vertices[g.id(6, 6, 6)], Vec3(6, 6, 6));
  EXPECT_EQ(g.mesh.vertices[g.id(6, 5, 6)], Vec3(6, 5, 6));
  expect_on_cube(g.mesh, g.n);
}

// A boundary vertex dragged along its face (a boundary quad with a small
// angle, the worst elements of fertility): it slides back on the surface,
// exactly on its face, and the minimum rises over the threshold.
TEST(RaiseWorstScaledJacobian, BoundaryVertexSlidesBackOnTheSurface) {
  test::GridInCube g(4);
  const std::size_t v = g.id(2, 2, 4);
  g.mesh.vertices[v] = Vec3(2.4, 2.35, 4.0);
  const std::vector<double> before = scaled_jacobians(g.mesh);
  ASSERT_GT(min_of(before), 0.0);
  ASSERT_LT(min_of(before), 0.5);
  raise_worst_scaled_jacobian(g.mesh, g.surface);
  const std::vector<double> after = scaled_jacobians(g.mesh);
  EXPECT_GT(min_of(after), 0.8);
  EXPECT_NEAR(g.mesh.vertices[v].z(), 4.0, 1e-12);
  EXPECT_LT((g.mesh.vertices[v] - Vec3(2, 2, 4)).norm(), 0.3);
  expect_on_cube(g.mesh, g.n);
}

// Two dragged vertices next to each other, one inside and one on the
// boundary, and a threshold above every hexahedron: the minimum never
// drops, whatever the threshold, and nothing inverts.
TEST(RaiseWorstScaledJacobian, MinimumNeverDrops) {
  test::GridInCube g(4);
  g.mesh.vertices[g.id(1, 2, 3)] = Vec3(1.3, 2.35, 3.3);
  g.mesh.vertices[g.id(1, 2, 4)] = Vec3(1.45, 1.7, 4.0);
  const double start = test::min_sj(g.mesh);
  ASSERT_GT(start, 0.0);
  for (double threshold : {0.3, 0.7, 1.0}) {
    HexMesh m = g.mesh;
    const RaiseWorstScaledJacobianReport r =
        raise_worst_scaled_jacobian(m, g.surface, {.threshold = threshold, .rings = 1});
    EXPECT_GE(r.min_after, start) << threshold;
    EXPECT_GE(test::min_sj(m), start) << threshold;
    expect_on_cube(m, g.n);
  }
}

// A perfect grid has no target: nothing moves.
TEST(RaiseWorstScaledJacobian, PerfectGridIsLeftAlone) {
  test::GridInCube g(3);
  const HexMesh start = g.mesh;
  const RaiseWorstScaledJacobianReport r = raise_worst_scaled_jacobian(g.mesh, g.surface);
  EXPECT_EQ(r.targets_before, 0u);
  EXPECT_EQ(r.patches, 0u);
  EXPECT_EQ(g.mesh.vertices, start.vertices);
}

}  // namespace
}  // namespace subfab
