// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/hexmesh.h"

#include <gtest/gtest.h>

#include "subfab/core/parallel.h"
#include "support/hex_test_shapes.h"
#include "support/test_shapes.h"

namespace subfab {
namespace {

TEST(Hexmesh, CapsuleIsAValidMeshOnItsSurface) {
  const Mesh m = test::capsule(1.0, 3.0, 32, 8, 24);
  HexMeshOptions options;
  options.subdivisions = 1;
  const HexMeshResult r = hexmesh(m, nullptr, options);
  EXPECT_EQ(r.structure_info.num_cubes, 2u);  // two terminal cubes
  EXPECT_EQ(r.structure_info.num_tubes, 1u);
  EXPECT_TRUE(r.check.valid());
  EXPECT_GT(r.min_sj, 0.3);
  EXPECT_GT(r.avg_sj, 0.6);  // one split only: coarse (0.89 with the automatic two)
  EXPECT_EQ(r.histogram[0], 0u);
  EXPECT_LT(r.mean_distance / r.diagonal, 0.01);
  EXPECT_LT(r.max_distance / r.diagonal, 0.05);
}

TEST(Hexmesh, TorusIsARingOfHexahedra) {
  const Mesh m = test::torus(48, 16, 2.0, 0.5);
  HexMeshOptions options;
  options.subdivisions = 1;
  const HexMeshResult r = hexmesh(m, nullptr, options);
  EXPECT_EQ(r.structure_info.num_cubes, 0u);  // a loop with no terminal node
  EXPECT_EQ(r.structure_info.num_tubes, 1u);
  EXPECT_TRUE(r.check.valid());
  EXPECT_GT(r.min_sj, 0.3);
  EXPECT_LT(r.mean_distance / r.diagonal, 0.005);
}

TEST(Hexmesh, GivenYSkeletonGivesOneBranchCube) {
  // a capsule with a Y skeleton would not fit; a given straight skeleton
  // with an extra inner node is used as it is
  const Mesh m = test::capsule(1.0, 3.0, 32, 8, 24);
  Skeleton s = test::line_skeleton(7, 3.0, 1.0);
  HexMeshOptions options;
  options.subdivisions = 1;
  const HexMeshResult r = hexmesh(m, &s, options);
  EXPECT_EQ(r.skeleton.num_nodes(), 7u);
  EXPECT_TRUE(r.check.valid());
  EXPECT_EQ(r.histogram[0], 0u);
}

TEST(Hexmesh, SameOutputWhateverTheThreads) {
  const Mesh m = test::torus(32, 12, 2.0, 0.5);
  HexMeshOptions options;
  options.subdivisions = 1;
  HexMesh one, two;
  {
    ThreadLimit limit(1);
    one = hexmesh(m, nullptr, options).mesh;
  }
  {
    ThreadLimit limit(2);
    two = hexmesh(m, nullptr, options).mesh;
  }
  EXPECT_EQ(one.hexes, two.hexes);
  EXPECT_EQ(one.vertices, two.vertices);
}

}  // namespace
}  // namespace subfab
