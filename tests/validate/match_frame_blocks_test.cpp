// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/validate/match_frame_blocks.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <limits>

#include "geometry/rotate_accurately.h"
#include "subfab/geometry/rotate_into_frame.h"
#include "support/block_test_shapes.h"

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

}  // namespace
}  // namespace subfab
