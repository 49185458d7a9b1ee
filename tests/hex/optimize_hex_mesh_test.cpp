// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/optimize_hex_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "subfab/core/error.h"

#include "subfab/hex/scaled_jacobian.h"
#include "support/hex_test_shapes.h"
#include "support/test_shapes.h"

namespace subfab {
namespace {

//! [0,3]^3 as 3 x 3 x 3 unit hexahedra; vertex (i,j,k) has index i + 4j + 16k.
HexMesh grid3() { return test::hex_grid(3, 3, 3); }

// Regression (issue 14): boundary vertices were put on their targets in one
// go after each split, which inverted the thin padding layer. A target deep
// inside, beyond the interior vertices below it, is now approached only as
// far as the elements stay valid.
TEST(OptimizeHexMesh, GuardedProjectionNeverInverts) {
  HexMesh m = grid3();
  const Mesh surface = test::cube(Vec3::Zero(), 3.0);
  std::vector<Vec3> targets = m.vertices;
  const std::size_t v = 1 + 4 * 1 + 16 * 3;  // (1,1,3) on the top face
  targets[v] = Vec3(1, 1, 0.5);                // below the interior vertices (1,1,2) and (1,1,1)
  OptimizeHexMeshOptions options{.passes = 5, .smooth = false, .targets = &targets};
  const OptimizeHexMeshReport r = optimize_hex_mesh(m, surface, options);
  EXPECT_EQ(r.num_inverted, 0u);
  EXPECT_GT(r.min_after, 0.0);
  EXPECT_GE(r.num_off_surface, 1u);
  EXPECT_LT(m.vertices[v].z(), 3.0);  // it did move towards its target

  // unguarded, the same target inverts the top layer
  HexMesh u = grid3();
  u.vertices[v] = targets[v];
  const std::vector<double> sj = scaled_jacobians(u);
  EXPECT_LT(*std::min_element(sj.begin(), sj.end()), 0.0);
}

TEST(OptimizeHexMesh, TargetsOfTheWrongSizeAreRejected) {
  HexMesh m = grid3();
  const std::vector<Vec3> targets(3, Vec3::Zero());
  OptimizeHexMeshOptions options{.targets = &targets};
  EXPECT_THROW(optimize_hex_mesh(m, test::cube(Vec3::Zero(), 3.0), options), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
