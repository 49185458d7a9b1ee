// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/compute_skeleton.h"

#include <gtest/gtest.h>

#include "support/hex_test_shapes.h"
#include "support/test_shapes.h"

namespace subfab {
namespace {

TEST(ComputeSkeleton, CapsuleGivesASegmentOnItsAxis) {
  const Mesh m = test::capsule(1.0, 3.0);
  const Skeleton s = compute_skeleton(m);
  ASSERT_GE(s.num_nodes(), 2u);
  const auto arcs = skeleton_arcs(s);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_FALSE(arcs[0].closed);
  for (std::size_t v = 0; v < s.num_nodes(); ++v) {
    EXPECT_LT(std::hypot(s.points[v].y(), s.points[v].z()), 0.1);
    EXPECT_LT(std::abs(s.points[v].x()), 4.0);
  }
  // radius near the middle is the tube's
  double best = 1e9, r_mid = 0;
  for (std::size_t v = 0; v < s.num_nodes(); ++v)
    if (std::abs(s.points[v].x()) < best) best = std::abs(s.points[v].x()), r_mid = s.radii[v];
  EXPECT_NEAR(r_mid, 1.0, 0.15);
}

TEST(ComputeSkeleton, TorusGivesARing) {
  const Skeleton s = compute_skeleton(test::torus(32, 12, 2.0, 0.5));
  const auto arcs = skeleton_arcs(s);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_TRUE(arcs[0].closed);
  for (std::size_t v = 0; v < s.num_nodes(); ++v) EXPECT_NEAR(s.points[v].head<2>().norm(), 2.0, 0.25);  // the flow shrinks rings a little
}

TEST(ComputeSkeleton, IsDeterministic) {
  // CGAL's flow orders some collapses by address: compute_skeleton runs it
  // in a deterministic arena, so repeated runs agree exactly
  const Mesh m = test::capsule(1.0, 2.0);
  const Skeleton a = compute_skeleton(m);
  std::vector<std::vector<int>> noise(1000, std::vector<int>(17));  // disturb the heap
  const Skeleton b = compute_skeleton(m);
  ASSERT_EQ(a.num_nodes(), b.num_nodes());
  for (std::size_t v = 0; v < a.num_nodes(); ++v) {
    EXPECT_EQ(a.points[v], b.points[v]);
    EXPECT_EQ(a.radii[v], b.radii[v]);
    EXPECT_EQ(a.neighbors[v], b.neighbors[v]);
  }
}

}  // namespace
}  // namespace subfab
