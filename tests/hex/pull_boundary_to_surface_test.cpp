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
  PullBoundaryOptions o;
  o.rings = 0;  // the vertex alone, its neighbourhood not re-optimised
  const PullBoundaryReport r = pull_boundary_to_surface(g.mesh, g.surface, o);
  EXPECT_EQ(r.off_before, 1u);
  EXPECT_EQ(r.off_after, 1u);
  EXPECT_EQ(r.held, 0u);
  const Vec3 p = g.mesh.vertices[g.id(1, 1, 2)];
  EXPECT_GT(p.z(), 2.2);  // still above the centre below it
  EXPECT_LT(p.z(), 2.6);  // partial moves were taken
  EXPECT_NEAR(r.max_off_after, p.z() - 2.0, 1e-12);
  EXPECT_GE(min_sj(g.mesh), before);
}

//! The stuck case above (main 31321b1 left that vertex 0.4 off the surface:
//! moving it alone inverts its hexahedra), on a 4 x 4 x 4 grid: the second
//! stage puts it on the surface in steps, its neighbourhood (the interior
//! vertex under it) following, and no hexahedron ends under the floor.
TEST(PullBoundaryToSurface, HeldVertexReachesTheSurfaceWithItsNeighbourhood) {
  test::GridInCube g(4);
  g.mesh.vertices[g.id(2, 2, 3)] = Vec3(2, 2, 4.2);  // an interior vertex above the top face
  g.mesh.vertices[g.id(2, 2, 4)] = Vec3(2, 2, 4.6);  // the top face's vertex above it
  const double before = min_sj(g.mesh);
  ASSERT_GT(before, 0.0);
  const PullBoundaryReport r = pull_boundary_to_surface(g.mesh, g.surface);
  EXPECT_EQ(r.off_before, 1u);
  EXPECT_EQ(r.held, 1u);
  EXPECT_EQ(r.snapped, 1u);
  EXPECT_EQ(r.off_after, 0u);
  EXPECT_LT(r.max_off_after, 1e-9);  // main: 0.4
  EXPECT_NEAR(g.mesh.vertices[g.id(2, 2, 4)].z(), 4.0, 1e-12);
  EXPECT_LT(g.mesh.vertices[g.id(2, 2, 3)].z(), 4.0);  // the interior vertex went back in
  EXPECT_GE(min_sj(g.mesh), std::min(before, 0.3));  // PullBoundaryOptions::patch_floor
  // every boundary vertex on the surface of the cube
  for (std::size_t v = 0; v < g.mesh.vertices.size(); ++v) {
    const Vec3& p = g.mesh.vertices[v];
    const double inside = std::min({p.x(), p.y(), p.z(), 4 - p.x(), 4 - p.y(), 4 - p.z()});
    EXPECT_GE(inside, -1e-12) << v;
  }
}

//! Every boundary vertex of a 4 x 4 x 4 grid pushed out by up to 0.4 and
//! every interior vertex jittered (fixed pseudo-random numbers): most come
//! back, and no hexahedron ends under min(the mesh's minimum before,
//! patch_floor).
TEST(PullBoundaryToSurface, MinimumKeptWhenManyVerticesAreHeld) {
  test::GridInCube g(4);
  unsigned state = 12345;
  const auto next = [&] {  // in [0, 1)
    state = state * 1103515245u + 12345u;
    return static_cast<double>((state >> 8) & 0xffff) / 65536.0;
  };
  for (std::size_t v = 0; v < g.mesh.vertices.size(); ++v) {
    Vec3& p = g.mesh.vertices[v];
    const bool boundary = std::min({p.x(), p.y(), p.z(), 4 - p.x(), 4 - p.y(), 4 - p.z()}) == 0.0;
    if (boundary) {
      p += 0.4 * next() * (p - Vec3(2, 2, 2)).normalized();
    } else {
      p += 0.2 * Vec3(next() - 0.5, next() - 0.5, next() - 0.5);
    }
  }
  const double before = min_sj(g.mesh);
  ASSERT_GT(before, 0.0);
  PullBoundaryOptions o;
  HexMesh first = g.mesh;
  o.rings = 0;  // the first stage alone
  const PullBoundaryReport r0 = pull_boundary_to_surface(first, g.surface, o);
  o.rings = PullBoundaryOptions{}.rings;
  const PullBoundaryReport r = pull_boundary_to_surface(g.mesh, g.surface, o);
  EXPECT_GT(r.off_before, 90u);
  EXPECT_LT(r.off_after, r.off_before / 10);
  EXPECT_LT(r.off_after, r0.off_after);
  EXPECT_GE(min_sj(g.mesh), std::min(before, o.patch_floor));
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
