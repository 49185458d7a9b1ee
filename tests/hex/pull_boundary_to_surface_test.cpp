// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/pull_boundary_to_surface.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "subfab/hex/scaled_jacobian.h"
#include "support/hex_test_shapes.h"
#include "support/test_shapes.h"

namespace subfab {
namespace {

using test::min_sj;

//! 2 x 2 x 2 unit hexahedra filling the cube [0,2]^3, its surface the cube.
struct Grid : test::GridInCube {
  Grid() : GridInCube(2) {}
};

TEST(PullBoundaryToSurface, OffSurfaceVertexReturnsWhenItCostsNothing) {
  Grid g;
  g.mesh.vertices[g.id(1, 1, 2)] = Vec3(1.1, 0.9, 2.3);  // the top face's centre, lifted off the surface
  const double before = min_sj(g.mesh);
  const PullBoundaryReport r = pull_boundary_to_surface(g.mesh, g.surface);
  EXPECT_EQ(r.off_before, 1u);
  EXPECT_EQ(r.off_after, 0u);
  EXPECT_NEAR(r.max_off_before, 0.3, 1e-12);
  EXPECT_GE(r.moves, 1u);
  EXPECT_NEAR(g.mesh.vertices[g.id(1, 1, 2)].z(), 2.0, 1e-12);  // its closest point, on the surface
  EXPECT_GE(min_sj(g.mesh), before);
}

TEST(PullBoundaryToSurface, MoveThatWouldInvertIsOnlyPartlyTaken) {
  Grid g;
  // the centre of the mesh raised above the top face, the top face's centre
  // above it: pulling that one back to z = 2 would invert its hexahedra, so
  // it moves only part of the way (each step keeping its worst hexahedron)
  g.mesh.vertices[g.id(1, 1, 1)] = Vec3(1, 1, 2.2);
  g.mesh.vertices[g.id(1, 1, 2)] = Vec3(1, 1, 2.6);
  const double before = min_sj(g.mesh);
  ASSERT_GT(before, 0.0);
  const PullBoundaryReport r = pull_boundary_to_surface(g.mesh, g.surface);
  EXPECT_EQ(r.off_before, 1u);
  EXPECT_EQ(r.off_after, 1u);
  const Vec3 p = g.mesh.vertices[g.id(1, 1, 2)];
  EXPECT_GT(p.z(), 2.2);  // still above the centre below it
  EXPECT_LT(p.z(), 2.6);  // partial moves were taken
  EXPECT_NEAR(r.max_off_after, p.z() - 2.0, 1e-12);
  EXPECT_GE(min_sj(g.mesh), before);
}

TEST(PullBoundaryToSurface, MeshOnTheSurfaceIsUnchanged) {
  Grid g;
  const HexMesh start = g.mesh;
  const PullBoundaryReport r = pull_boundary_to_surface(g.mesh, g.surface);
  EXPECT_EQ(r.off_before, 0u);
  EXPECT_EQ(r.moves, 0u);
  EXPECT_EQ(g.mesh.vertices, start.vertices);
}

}  // namespace
}  // namespace subfab
