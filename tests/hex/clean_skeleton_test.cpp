// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/clean_skeleton.h"

#include <gtest/gtest.h>

#include "support/hex_test_shapes.h"

namespace subfab {
namespace {

std::size_t count_degree(const Skeleton& s, std::size_t d) {
  std::size_t n = 0;
  for (const auto& nb : s.neighbors) n += nb.size() == d;
  return n;
}

TEST(CleanSkeleton, StraightChainKeepsOnlyItsEnds) {
  CleanSkeletonReport report;
  const Skeleton s = clean_skeleton(test::line_skeleton(9), {}, &report);
  EXPECT_EQ(s.num_nodes(), 2u);
  EXPECT_EQ(report.nodes_dropped, 7u);
  EXPECT_EQ(s.num_edges(), 1u);
}

TEST(CleanSkeleton, CollapsesTwoNearbyBranchNodes) {
  // an H: two branch nodes 0.6 apart with radius 0.5 each, two legs each
  Skeleton s;
  const int a = s.add_node(Vec3(0, 0, 0), 0.5), b = s.add_node(Vec3(0.6, 0, 0), 0.5);
  s.add_edge(a, b);
  for (const Vec3& d : {Vec3(-3, 1, 0), Vec3(-3, -1, 0)}) s.add_edge(a, s.add_node(d, 0.3));
  for (const Vec3& d : {Vec3(3.6, 1, 0), Vec3(3.6, -1, 0)}) s.add_edge(b, s.add_node(d, 0.3));
  CleanSkeletonReport report;
  const Skeleton c = clean_skeleton(s, {}, &report);
  EXPECT_EQ(report.branches_collapsed, 1u);
  EXPECT_EQ(c.num_nodes(), 5u);
  EXPECT_EQ(count_degree(c, 4), 1u);
  EXPECT_NEAR(c.points[0].x(), 0.3, 1e-12);
}

TEST(CleanSkeleton, PrunesAShortSpur) {
  Skeleton s = test::line_skeleton(7, 3.0, 1.0);  // nodes at x = -3..3
  s.add_edge(3, s.add_node(Vec3(0, 0.8, 0), 0.2));  // spur of length 0.8 < radius 1
  CleanSkeletonReport report;
  const Skeleton c = clean_skeleton(s, {}, &report);
  EXPECT_EQ(report.branches_pruned, 1u);
  EXPECT_EQ(count_degree(c, 3), 0u);
  EXPECT_EQ(count_degree(c, 1), 2u);
}

TEST(CleanSkeleton, KeepsALoop) {
  const Skeleton c = clean_skeleton(test::ring_skeleton(12));
  EXPECT_GE(c.num_nodes(), 3u);
  EXPECT_EQ(count_degree(c, 2), c.num_nodes());
}

}  // namespace
}  // namespace subfab
