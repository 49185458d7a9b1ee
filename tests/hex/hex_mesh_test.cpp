// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/hex_mesh.h"

#include <gtest/gtest.h>

#include "support/hex_test_shapes.h"

namespace subfab {
namespace {

//! Two unit cubes side by side along x, sharing a face.
HexMesh two_cubes() { return test::hex_grid(2, 1, 1); }

TEST(HexMesh, TwoCubesShareOneQuad) {
  const HexMeshCheck c = check_hex_mesh(two_cubes());
  EXPECT_TRUE(c.valid());
  EXPECT_EQ(c.num_interior_quads, 1u);
  EXPECT_EQ(c.num_boundary_quads, 10u);
  EXPECT_EQ(boundary_quads(two_cubes()).size(), 10u);
}

TEST(HexMesh, ACrackIsFound) {
  HexMesh m = two_cubes();
  // the second cube gets its own copy of the shared face: a crack
  for (int& v : m.hexes[1])
    if (v % 3 == 1) {
      m.vertices.push_back(m.vertices[static_cast<std::size_t>(v)]);
      v = static_cast<int>(m.vertices.size()) - 1;
    }
  const HexMeshCheck c = check_hex_mesh(m);
  EXPECT_FALSE(c.valid());
  EXPECT_EQ(c.num_coincident_vertices, 4u);
}

TEST(HexMesh, AFlippedNeighbourIsFound) {
  HexMesh m = two_cubes();
  Hex& h = m.hexes[1];
  h = {h[4], h[5], h[6], h[7], h[0], h[1], h[2], h[3]};  // inside out
  EXPECT_EQ(check_hex_mesh(m).num_same_side_quads, 1u);
}

}  // namespace
}  // namespace subfab
