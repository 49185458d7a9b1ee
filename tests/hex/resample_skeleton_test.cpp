// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/resample_skeleton.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/hex_test_shapes.h"

namespace subfab {
namespace {

TEST(ResampleSkeleton, ThinTubeIsSplitUntilSpheresOverlap) {
  // length 8, radius 0.5: an interval of length 4 has its midpoint 2 from
  // its ends (2 > 0.5 + 0.5: split); one of length 2 has it 1 away (not
  // split), so 4 intervals of length 2
  Skeleton s = test::line_skeleton(3, 4.0, 0.5);
  const Skeleton r = resample_skeleton(s);
  const auto arcs = skeleton_arcs(r);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_EQ(arcs[0].nodes.size(), 5u);
  for (std::size_t i = 1; i < arcs[0].nodes.size(); ++i)
    EXPECT_NEAR((r.points[static_cast<std::size_t>(arcs[0].nodes[i])] -
                 r.points[static_cast<std::size_t>(arcs[0].nodes[i - 1])]).norm(), 2.0, 1e-12);
}

TEST(ResampleSkeleton, NeckBetweenSamplesIsSplitOnlyWhenAsked) {
  // a thick tube (radius 5, length 2: one inner node by D.4) with a neck of
  // radius 0.5 at x = 0.5 (21 nodes from -1 to 1, node 15 at 0.5)
  Skeleton s = test::line_skeleton(21, 1.0, 5.0);
  s.radii[15] = 0.5;
  EXPECT_EQ(resample_skeleton(s).num_nodes(), 3u);  // default: the thesis's criterion only
  ResampleSkeletonOptions options;
  options.neck_ratio = 0.6;
  const Skeleton r = resample_skeleton(s, options);
  // [0, 1] is split at 0.5 (forced), then [0.5, 1] (x in [0, 1]) holds the
  // neck node strictly inside: split at x = 0.5, its ends then have radius
  // ~0.5, so it stops
  ASSERT_EQ(r.num_nodes(), 4u);
  bool at_neck = false;
  for (std::size_t v = 0; v < r.num_nodes(); ++v) at_neck = at_neck || std::abs(r.points[v].x() - 0.5) < 1e-9;
  EXPECT_TRUE(at_neck);
}

TEST(ResampleSkeleton, ThickTubeKeepsOneInnerNode) {
  const Skeleton r = resample_skeleton(test::line_skeleton(20, 1.0, 5.0));
  EXPECT_EQ(r.num_nodes(), 3u);
  EXPECT_NEAR(r.points[2].x(), 0.0, 1e-12);  // the midpoint
  EXPECT_EQ(r.num_edges(), 2u);
}

TEST(ResampleSkeleton, YKeepsItsBranchNodeAndEnds) {
  const Skeleton r = resample_skeleton(test::y_skeleton(10, 3.6, 0.5));
  std::size_t branch = 0, ends = 0;
  for (const auto& nb : r.neighbors) branch += nb.size() == 3, ends += nb.size() == 1;
  EXPECT_EQ(branch, 1u);
  EXPECT_EQ(ends, 3u);
  EXPECT_EQ(r.points[0], Vec3::Zero());
  EXPECT_EQ(skeleton_arcs(r).size(), 3u);
  EXPECT_EQ(r.num_nodes(), 1u + 3u * 2u);  // each branch of length 3.6 split into 2 intervals of 1.8
}

TEST(ResampleSkeleton, RingStaysAClosedCycle) {
  const Skeleton r = resample_skeleton(test::ring_skeleton(64, 2.0, 5.0));
  const auto arcs = skeleton_arcs(r);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_TRUE(arcs[0].closed);
  EXPECT_EQ(r.num_nodes(), 3u);
}

}  // namespace
}  // namespace subfab
