// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/build_tubular_structure.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>

#include "subfab/hex/resample_skeleton.h"
#include "subfab/hex/scaled_jacobian.h"
#include "support/hex_test_shapes.h"

namespace subfab {
namespace {

double min_sj(const HexMesh& m) {
  const auto sj = scaled_jacobians(m);
  return *std::min_element(sj.begin(), sj.end());
}

TEST(BuildTubularStructure, CapsuleIsATubeBetweenTwoTerminalCubes) {
  const Skeleton s = resample_skeleton(test::line_skeleton(3, 4.0, 0.5));  // 5 nodes, 3 inner
  const TubularStructure t = build_tubular_structure(s);
  EXPECT_EQ(t.num_cubes, 2u);
  EXPECT_EQ(t.num_tubes, 1u);
  EXPECT_EQ(t.num_subdivided_cubes, 0u);
  EXPECT_EQ(t.mesh.num_hexes(), 2u + 4u);  // two cubes, four layers between them
  const HexMeshCheck c = check_hex_mesh(t.mesh);
  EXPECT_TRUE(c.valid());
  EXPECT_EQ(c.num_interior_quads, 5u);
  EXPECT_EQ(c.num_boundary_quads, 6u * 4u + 2u);
  EXPECT_GT(min_sj(t.mesh), 0.99);  // straight: all boxes
}

TEST(BuildTubularStructure, YJunctionIsConforming) {
  const Skeleton s = resample_skeleton(test::y_skeleton(10, 3.6, 0.5));
  const TubularStructure t = build_tubular_structure(s);
  EXPECT_EQ(t.num_cubes, 4u);
  EXPECT_EQ(t.num_tubes, 3u);
  EXPECT_EQ(t.num_subdivided_cubes, 0u);
  EXPECT_NEAR(t.worst_arc_angle_deg, 30.0, 1e-6);  // arcs 120 degrees apart on faces 90 degrees apart
  EXPECT_TRUE(check_hex_mesh(t.mesh).valid());
  EXPECT_GT(min_sj(t.mesh), 0.0);
}

TEST(BuildTubularStructure, RingIsAClosedTube) {
  const Skeleton s = resample_skeleton(test::ring_skeleton(32, 2.0, 0.3));
  const TubularStructure t = build_tubular_structure(s);
  EXPECT_EQ(t.num_cubes, 0u);
  EXPECT_EQ(t.num_tubes, 1u);
  const HexMeshCheck c = check_hex_mesh(t.mesh);
  EXPECT_TRUE(c.valid());
  EXPECT_EQ(c.num_interior_quads, t.mesh.num_hexes());  // a ring: as many shared quads as layers
  EXPECT_EQ(c.num_boundary_quads, 4 * t.mesh.num_hexes());
  EXPECT_GT(min_sj(t.mesh), 0.9);
}

TEST(BuildTubularStructure, EightArmsSubdivideTheCube) {
  Skeleton s;
  s.add_node(Vec3::Zero(), 0.5);
  for (int i = 0; i < 8; ++i) {  // the 8 cube diagonals
    const Vec3 d(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    const int a = s.add_node(2.0 * d, 0.3), b = s.add_node(4.0 * d, 0.3);
    s.add_edge(0, a);
    s.add_edge(a, b);
  }
  const TubularStructure t = build_tubular_structure(resample_skeleton(s));
  EXPECT_EQ(t.num_subdivided_cubes, 1u);
  EXPECT_TRUE(check_hex_mesh(t.mesh).valid());
  EXPECT_GT(min_sj(t.mesh), 0.0);
}

TEST(BuildTubularStructure, LoopBackToTheSameNode) {
  // a branch node with a terminal arc and a loop that returns to it
  Skeleton s;
  s.add_node(Vec3::Zero(), 0.3);
  s.add_edge(0, s.add_node(Vec3(-3, 0, 0), 0.3));
  int prev = 0;
  for (int i = 1; i < 12; ++i) {
    const double a = 2 * std::numbers::pi * i / 12;
    const int v = s.add_node(Vec3(2 - 2 * std::cos(a), 2 * std::sin(a), 0), 0.3);
    s.add_edge(prev, v);
    prev = v;
  }
  s.add_edge(prev, 0);
  const TubularStructure t = build_tubular_structure(resample_skeleton(s));
  EXPECT_EQ(t.num_tubes, 2u);
  EXPECT_TRUE(check_hex_mesh(t.mesh).valid());
  EXPECT_GT(min_sj(t.mesh), 0.0);
}

}  // namespace
}  // namespace subfab
