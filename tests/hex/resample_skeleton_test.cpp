// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/resample_skeleton.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

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


// Regression (issue 14, rocker arm): the spheres of a loop as thick as its
// bend overlap across the hole, so D.4's criterion alone kept three samples
// on the rocker arm's loop, whose straight tubes cut across its hole (hex
// boundary vertices 0.095 of the diagonal from the surface). A ring of
// radius 2, tube radius 2: the thirds' ends are 2 apart (under 2 + 2: D.4
// does not split), their chords stray 2 (1 - cos 60) = 1 from the ring, more
// than 0.25 x 2: split; the sixths' chords 0.27, under 0.5: kept.
TEST(ResampleSkeleton, LoopIsSplitUntilItsChordsFollowIt) {
  const Skeleton s = test::ring_skeleton(64, 2.0, 2.0);
  ResampleSkeletonOptions plain;
  plain.bend_ratio = 0;
  EXPECT_EQ(resample_skeleton(s, plain).num_nodes(), 3u);
  const Skeleton r = resample_skeleton(s);  // bend_ratio 0.25 by default
  ASSERT_EQ(r.num_nodes(), 6u);
  for (std::size_t v = 0; v < r.num_nodes(); ++v) EXPECT_NEAR(r.points[v].norm(), 2.0, 3e-3);  // on the 64-gon
  const auto arcs = skeleton_arcs(r);
  ASSERT_EQ(arcs.size(), 1u);
  EXPECT_TRUE(arcs[0].closed);
}

// The bend criterion is for loops only: on open arcs it split the wiggles of
// the computed skeletons into short, thick layers (cactus got inverted
// elements, bob's minimum fell from .66 to .16). A half circle of radius 2,
// tube radius 1: D.4 splits it once (the midpoint is 2.83 from the ends, the
// quarters 1.53 from them, under 1 + 1), though a half's chord strays 0.59.
TEST(ResampleSkeleton, OpenArcIsNotSplitForItsBend) {
  Skeleton s;
  for (int i = 0; i <= 32; ++i) {
    const double a = std::numbers::pi * (1.0 - i / 32.0);
    s.add_node(Vec3(2 * std::cos(a), 2 * std::sin(a), 0), 1.0);
    if (i > 0) s.add_edge(i - 1, i);
  }
  EXPECT_EQ(resample_skeleton(s).num_nodes(), 3u);
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
