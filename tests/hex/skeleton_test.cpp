// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/skeleton.h"

#include <gtest/gtest.h>

#include "subfab/core/error.h"
#include "support/hex_test_shapes.h"

namespace subfab {
namespace {

TEST(SkeletonArcs, LineIsOneArc) {
  const Skeleton s = test::line_skeleton(7);
  const auto arcs = skeleton_arcs(s);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_EQ(arcs[0].nodes.size(), 7u);
  EXPECT_EQ(arcs[0].nodes.front(), 0);
  EXPECT_EQ(arcs[0].nodes.back(), 6);
  EXPECT_FALSE(arcs[0].closed);
  EXPECT_NEAR(arc_length(s, arcs[0]), 6.0, 1e-12);
}

TEST(SkeletonArcs, YHasThreeArcsFromTheCentre) {
  const Skeleton s = test::y_skeleton(5);
  const auto arcs = skeleton_arcs(s);
  ASSERT_EQ(arcs.size(), 3u);
  for (const auto& arc : arcs) {
    EXPECT_EQ(arc.nodes.front(), 0);
    EXPECT_EQ(arc.nodes.size(), 6u);
    EXPECT_EQ(s.neighbors[static_cast<std::size_t>(arc.nodes.back())].size(), 1u);
  }
}

TEST(SkeletonArcs, RingIsOneClosedArc) {
  const Skeleton s = test::ring_skeleton(10);
  const auto arcs = skeleton_arcs(s);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_TRUE(arcs[0].closed);
  EXPECT_EQ(arcs[0].nodes.size(), 11u);
  EXPECT_EQ(arcs[0].nodes.front(), arcs[0].nodes.back());
  EXPECT_EQ(num_skeleton_components(s), 1u);
}

TEST(CheckSkeleton, RejectsAsymmetricAdjacency) {
  Skeleton s = test::line_skeleton(3);
  s.neighbors[0].push_back(2);
  EXPECT_THROW(check_skeleton(s), InvalidArgumentError);
  EXPECT_NO_THROW(check_skeleton(test::y_skeleton()));
}

}  // namespace
}  // namespace subfab
