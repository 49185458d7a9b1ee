// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/pillow_hex_mesh.h"

#include <gtest/gtest.h>

#include <map>

#include "subfab/hex/scaled_jacobian.h"
#include "subfab/hex/subdivide_hex_mesh.h"
#include "support/hex_test_shapes.h"

namespace subfab {
namespace {

HexMesh unit_cube() { return test::unit_hex_cube(); }

TEST(PillowHexMesh, CubeGetsSixPaddingHexahedra) {
  HexMesh m = unit_cube();
  const std::vector<int> outer = pillow_hex_mesh(m);
  ASSERT_EQ(m.num_hexes(), 7u);
  ASSERT_EQ(m.num_vertices(), 16u);
  for (std::size_t v = 0; v < 8; ++v) {
    ASSERT_GE(outer[v], 8);
    // push the copies out: a cube of side 3 around the unit cube
    m.vertices[static_cast<std::size_t>(outer[v])] = 3.0 * (m.vertices[v] - Vec3::Constant(0.5)) + Vec3::Constant(0.5);
  }
  const HexMeshCheck c = check_hex_mesh(m);
  EXPECT_TRUE(c.valid());
  EXPECT_EQ(c.num_boundary_quads, 6u);
  EXPECT_EQ(c.num_interior_quads, 6u + 12u);
  for (std::size_t h = 0; h < m.num_hexes(); ++h) EXPECT_GT(scaled_jacobian(m, h), 0.0);
  // every padding hexahedron has exactly one face on the boundary
  std::map<std::array<int, 4>, int> boundary;
  for (Quad q : boundary_quads(m)) {
    std::sort(q.begin(), q.end());
    boundary[q] = 1;
  }
  for (std::size_t h = 1; h < m.num_hexes(); ++h) {
    int on = 0;
    for (int f = 0; f < 6; ++f) {
      Quad q = hex_face(m.hexes[h], f);
      std::sort(q.begin(), q.end());
      on += boundary.count(q) ? 1 : 0;
    }
    EXPECT_EQ(on, 1);
  }
}

TEST(SubdivideHexMesh, CubeSplitsIntoEightCubes) {
  const HexMesh m = subdivide_hex_mesh(unit_cube());
  ASSERT_EQ(m.num_hexes(), 8u);
  EXPECT_EQ(m.num_vertices(), 27u);
  for (std::size_t h = 0; h < 8; ++h) EXPECT_NEAR(scaled_jacobian(m, h), 1.0, 1e-15);
  const HexMeshCheck c = check_hex_mesh(m);
  EXPECT_TRUE(c.valid());
  EXPECT_EQ(c.num_boundary_quads, 24u);
  EXPECT_EQ(c.num_interior_quads, 12u);
}

TEST(SubdivideHexMesh, SharedFacesStayShared) {
  HexMesh m = unit_cube();
  pillow_hex_mesh(m);
  for (std::size_t v = 8; v < 16; ++v) m.vertices[v] = 3.0 * (m.vertices[v] - Vec3::Constant(0.5)) + Vec3::Constant(0.5);
  const HexMesh s = subdivide_hex_mesh(subdivide_hex_mesh(m));
  EXPECT_EQ(s.num_hexes(), 7u * 64u);
  const HexMeshCheck c = check_hex_mesh(s);
  EXPECT_TRUE(c.valid());
  EXPECT_EQ(c.num_boundary_quads, 6u * 16u);
}

}  // namespace
}  // namespace subfab
