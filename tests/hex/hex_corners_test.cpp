// SPDX-License-Identifier: GPL-3.0-or-later
#include "hex/hex_corners.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "subfab/hex/scaled_jacobian.h"
#include "support/hex_test_shapes.h"

namespace subfab {
namespace {

//! One distorted hexahedron (valid, no symmetry).
HexMesh skewed_hex() {
  HexMesh m;
  m.vertices = {Vec3(0, 0, 0),        Vec3(1.2, 0.1, 0),   Vec3(1.1, 0.9, 0.2), Vec3(-0.1, 1, 0.1),
                Vec3(0.1, -0.1, 1),   Vec3(1, 0.2, 1.3),   Vec3(1.3, 1.1, 0.9), Vec3(0, 0.8, 1.1)};
  m.hexes = {{0, 1, 2, 3, 4, 5, 6, 7}};
  return m;
}

TEST(HexCorners, EveryVertexMovesFourCornersOfEachHex) {
  const HexMesh m = test::hex_grid(2, 2, 2);
  const auto corners = detail::vertex_corners(m);
  // the centre vertex (1,1,1) is in all 8 hexahedra, 4 corners each
  EXPECT_EQ(corners[1 + 3 * 1 + 9 * 1].size(), 32u);
  // a grid corner is in one hexahedron
  EXPECT_EQ(corners[0].size(), 4u);
}

TEST(HexCorners, DeterminantsGiveTheScaledJacobian) {
  const HexMesh m = skewed_hex();
  double worst = 1;
  for (int c = 0; c < 8; ++c) worst = std::min(worst, detail::corner_determinant(m, {0, c}));
  EXPECT_DOUBLE_EQ(worst, scaled_jacobian(m, 0));
}

TEST(HexCorners, GradientMatchesCentralDifferences) {
  HexMesh m = skewed_hex();
  for (int c = 0; c < 8; ++c)
    for (int v = 0; v < 8; ++v) {
      Vec3 g;
      detail::corner_determinant_gradient(m, {0, c}, v, g);
      for (int a = 0; a < 3; ++a) {
        const double h = 1e-6, x = m.vertices[static_cast<std::size_t>(v)][a];
        m.vertices[static_cast<std::size_t>(v)][a] = x + h;
        const double up = detail::corner_determinant(m, {0, c});
        m.vertices[static_cast<std::size_t>(v)][a] = x - h;
        const double down = detail::corner_determinant(m, {0, c});
        m.vertices[static_cast<std::size_t>(v)][a] = x;
        EXPECT_NEAR(g[a], (up - down) / (2 * h), 1e-6) << "corner " << c << " vertex " << v << " axis " << a;
      }
    }
}

}  // namespace
}  // namespace subfab
