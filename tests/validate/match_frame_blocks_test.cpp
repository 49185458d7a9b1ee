// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/validate/match_frame_blocks.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <limits>

#include "geometry/rotate_accurately.h"
#include "subfab/geometry/rotate_into_frame.h"
#include "support/block_test_shapes.h"
#include "validate/validate_booleans.h"

namespace subfab {
namespace {

// A unit cube cut in two halves in a frame turned from the input's; the
// input is the cube turned back (as a model decompose orients), the
// exported halves are the frame halves rounded back vertex by vertex.
struct TurnedHalves {
  Eigen::Matrix3d rotation;  // canonical = rotation x input
  Mesh input;
  std::vector<Mesh> frame, exported;
};

Mesh turned(const Mesh& m, const Eigen::Matrix3d& r) {
  Mesh out = m;
  for (Vec3& v : out.vertices) v = detail::rotate_accurately(r, v);
  return out;
}

TurnedHalves turned_halves() {
  TurnedHalves t;
  t.rotation = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d back = t.rotation.transpose();
  t.input = turned(test::box_solid({0, 0, 0}, {1, 1, 1}), back);
  // The frame blocks hold the turned input's own vertices at its corners.
  const Mesh frame_input = rotate_into_frame(t.input, t.rotation, kFrameSnapTolerance);
  const BoundingBox fb = bounding_box(frame_input);
  const double mid = 0.5 * (fb.min.z() + fb.max.z());
  t.frame = {test::box_solid(fb.min, {fb.max.x(), fb.max.y(), mid}),
             test::box_solid({fb.min.x(), fb.min.y(), mid}, fb.max)};
  for (const Mesh& f : t.frame) t.exported.push_back(turned(f, back));
  return t;
}

FrameMatch match(const TurnedHalves& t) {
  return match_frame_blocks(t.input, {&t.exported[0], &t.exported[1]}, {&t.frame[0], &t.frame[1]}, t.rotation);
}

TEST(MatchFrameBlocks, FrameBlocksRoundedBackMatchWithinRounding) {
  const TurnedHalves t = turned_halves();
  const FrameMatch m = match(t);
  EXPECT_TRUE(m.frame_error.empty()) << m.frame_error;
  EXPECT_EQ(m.num_refused(), 0u) << m.refused[0] << m.refused[1];
  // the turned input: rounding and snapping only; the halves: one rounding per coordinate
  EXPECT_LT(m.input_offset, 1e-8);
  EXPECT_LT(m.block_offset, 1e-14);
  EXPECT_GE(m.stretch, 1.0);
  EXPECT_LT(m.stretch, 1.0 + 1e-13);
  EXPECT_GE(m.rounding(), 2.0 * m.block_offset);
  EXPECT_LT(m.rounding(), 1e-7);
  EXPECT_EQ(m.input.num_vertices(), t.input.num_vertices());
}

// A frame block that does not round to its exported block (a vertex moved,
// faces changed, a vertex missing) is refused: it cannot stand in for the
// exported block in check 10.
TEST(MatchFrameBlocks, ATamperedFrameBlockIsRefused) {
  TurnedHalves t = turned_halves();
  t.frame[1].vertices[3].z() += 1e-3;
  FrameMatch m = match(t);
  EXPECT_TRUE(m.refused[0].empty()) << m.refused[0];
  ASSERT_FALSE(m.refused[1].empty());
  EXPECT_NE(m.refused[1].find("vertex 3"), std::string::npos) << m.refused[1];
  EXPECT_EQ(m.num_refused(), 1u);
  EXPECT_LT(m.block_offset, 1e-14);  // the refused block's offset is not counted

  t = turned_halves();
  std::swap(t.frame[0].faces[0][0], t.frame[0].faces[0][1]);
  m = match(t);
  ASSERT_FALSE(m.refused[0].empty());
  EXPECT_NE(m.refused[0].find("faces"), std::string::npos) << m.refused[0];

  t = turned_halves();
  t.frame[0].vertices.push_back(Vec3::Zero());
  EXPECT_FALSE(match(t).refused[0].empty());
  EXPECT_FALSE(match_frame_blocks(t.input, {&t.exported[0]}, {nullptr}, t.rotation).refused[0].empty());
}

TEST(MatchFrameBlocks, ARotationThatIsNotOneRefusesEveryBlock) {
  TurnedHalves t = turned_halves();
  t.rotation(0, 0) *= 1.001;
  const FrameMatch m = match(t);
  EXPECT_FALSE(m.frame_error.empty());
  EXPECT_EQ(m.num_refused(), 2u);
  Eigen::Matrix3d mirror = Eigen::Matrix3d::Identity();
  mirror(2, 2) = -1;
  EXPECT_FALSE(match_frame_blocks(t.input, {&t.exported[0]}, {&t.frame[0]}, mirror).frame_error.empty());
}

// Check 4 in the frame: the volume of an exported block outside the input,
// bounded from its frame block's. Known answers: the halves lie inside (0),
// a top half raised by 0.25 sticks out by 0.25 (a unit square x 0.25); the
// bound is never below the exact volume of the exported block outside the
// input and exceeds it by the rounding's share only.
TEST(OutsideVolumeBound, BoundsTheExportedBlocksVolumeOutsideFromItsFrameBlocks) {
  TurnedHalves t = turned_halves();
  const Mesh frame_input = rotate_into_frame(t.input, t.rotation, kFrameSnapTolerance);
  const BoundingBox fb = bounding_box(frame_input);
  t.frame[1] = test::box_solid({fb.min.x(), fb.min.y(), 0.5 * (fb.min.z() + fb.max.z())},
                               {fb.max.x(), fb.max.y(), fb.max.z() + 0.25});
  t.exported[1] = turned(t.frame[1], t.rotation.transpose());
  const FrameMatch m = match(t);
  ASSERT_EQ(m.num_refused(), 0u) << m.refused[0] << m.refused[1];
  for (std::size_t i = 0; i < 2; ++i) {
    const double in_frame = detail::exact_volume_outside(t.frame[i], m.input);
    const double bound = outside_volume_bound(in_frame, t.exported[i], t.input, m);
    const double exact = detail::exact_volume_outside(t.exported[i], t.input);
    EXPECT_GE(bound, exact) << i;
    EXPECT_LE(bound, exact + 1e-8) << i;  // offsets ~1e-9 (the input's snapping) x areas ~6
    EXPECT_NEAR(exact, i == 0 ? 0.0 : 0.25, 1e-8) << i;
  }
}

// An exported block lying off its frame block by up to the offset allowed
// (here 4e-7, its top pushed out of the input): the frame block is inside,
// the bound still covers what the exported block has outside.
TEST(OutsideVolumeBound, HoldsWhenTheExportedBlockLiesOffItsFrameBlock) {
  TurnedHalves t = turned_halves();
  const Vec3 up = t.rotation.transpose() * Vec3::UnitZ();
  Mesh& top = t.exported[1];
  const BoundingBox fb = bounding_box(t.frame[1]);
  for (std::size_t v = 0; v < top.num_vertices(); ++v)
    if (t.frame[1].vertices[v].z() == fb.max.z()) top.vertices[v] += 4e-7 * up;
  const FrameMatch m = match(t);
  ASSERT_EQ(m.num_refused(), 0u) << m.refused[1];
  EXPECT_GE(m.block_offset, 4e-7 * (1 - 1e-9));
  const double exact = detail::exact_volume_outside(top, t.input);
  EXPECT_GT(exact, 3e-7);  // the unit top face raised by ~4e-7
  EXPECT_EQ(detail::exact_volume_outside(t.frame[1], m.input), 0.0);
  const double bound = outside_volume_bound(0.0, top, t.input, m);
  EXPECT_GE(bound, exact);
  EXPECT_LT(bound, 1e-5);
}

// Check 3 in the frame: the overlap of two exported blocks bounded from
// their frame blocks'. The halves only touch (0); the top half lowered by
// 0.1 into the bottom one overlaps it by 0.1 (a unit square x 0.1). The
// bound is never below the exact overlap of the exported blocks.
TEST(OverlapVolumeBound, BoundsTheExportedBlocksOverlapFromTheirFrameBlocks) {
  for (const double down : {0.0, 0.1}) {
    TurnedHalves t = turned_halves();
    for (Vec3& v : t.frame[1].vertices) v.z() -= down;
    t.exported[1] = turned(t.frame[1], t.rotation.transpose());
    const FrameMatch m = match(t);
    ASSERT_EQ(m.num_refused(), 0u) << m.refused[0] << m.refused[1];
    const double in_frame = detail::exact_blocks_overlap(t.frame[0], t.frame[1]);
    const double bound = overlap_volume_bound(in_frame, t.exported[0], t.exported[1], m);
    const double exact = detail::exact_blocks_overlap(t.exported[0], t.exported[1]);
    EXPECT_NEAR(exact, down, 1e-12) << down;
    EXPECT_GE(bound, exact) << down;
    EXPECT_LE(bound, exact * (1 + 1e-8) + 1e-8) << down;  // the offsets x areas ~6, the rounding up
  }
}

}  // namespace
}  // namespace subfab
