// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/snap_and_shrink.h"

#include <gtest/gtest.h>

#include <random>

#include "geometry/solid_index.h"
#include "support/voxel_solid.h"
#include "subfab/core/error.h"

namespace subfab {
namespace {

using test::Cell;

HeightBox hb(const Vec3& lo, const Vec3& hi, Axis axis) { return HeightBox{Box3{lo, hi}, axis, -1}; }

//! Per face, the number of boxes covering it.
std::vector<int> cover_counts(const detail::SolidIndex& index, const std::vector<HeightBox>& boxes) {
  std::vector<int> count(static_cast<std::size_t>(index.num_faces()), 0);
  for (const HeightBox& b : boxes)
    for (int f : index.faces_covered(b)) ++count[static_cast<std::size_t>(f)];
  return count;
}

void expect_valid_and_covering(const Mesh& mesh, const std::vector<HeightBox>& in, const std::vector<HeightBox>& out) {
  const detail::SolidIndex index(mesh);
  ASSERT_EQ(in.size(), out.size());
  for (const HeightBox& b : out) {
    EXPECT_TRUE(index.box_is_valid(b));
    EXPECT_GT(b.box.volume(), 0.0);
  }
  const std::vector<int> before = cover_counts(index, in), after = cover_counts(index, out);
  for (std::size_t f = 0; f < before.size(); ++f)
    if (before[f] > 0) {
      EXPECT_GT(after[f], 0) << "face " << f << " lost its cover";
    }
}

std::size_t num_overlapping_pairs(const std::vector<HeightBox>& boxes) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size(); ++j) n += boxes[i].box.overlaps(boxes[j].box);
  return n;
}

const Mesh& bar() {  // [0,10] x [0,1] x [0,1]
  static const Mesh mesh = test::union_of_boxes({{{0, 0, 0}, {10, 1, 1}}});
  return mesh;
}

TEST(SnapAndShrink, ClosesASmallGapByEnlarging) {
  const std::vector<HeightBox> boxes = {hb({0, 0, 0}, {4.75, 1, 1}, Axis::PosZ), hb({5, 0, 0}, {10, 1, 1}, Axis::PosZ)};
  SnapShrinkOptions options;
  options.snap_distance = 0.5;
  const SnapShrinkResult r = snap_and_shrink(bar(), boxes, options);
  EXPECT_EQ(r.num_snapped, 1);
  EXPECT_EQ(r.boxes[0].box.max.x(), 5.0);  // the left box grew onto the right one
  EXPECT_EQ(r.boxes[1].box.min.x(), 5.0);
  expect_valid_and_covering(bar(), boxes, r.boxes);
}

TEST(SnapAndShrink, AlignsNearlyCoincidentTops) {
  // Two +z boxes whose tops differ by 0.25: carving them would leave a
  // sliver; snapping aligns the tops.
  const Mesh mesh = test::union_of_boxes({{{0, 0, 0}, {10, 1, 2}}});
  const std::vector<HeightBox> boxes = {hb({0, 0, 0}, {6, 1, 2}, Axis::PosZ), hb({4, 0, 0}, {10, 1, 2.25}, Axis::PosZ)};
  SnapShrinkOptions options;
  options.snap_distance = 0.5;
  options.shrink = false;
  const SnapShrinkResult r = snap_and_shrink(mesh, boxes, options);
  EXPECT_GE(r.num_snapped, 1);
  EXPECT_EQ(r.boxes[0].box.max.z(), r.boxes[1].box.max.z());
  expect_valid_and_covering(mesh, boxes, r.boxes);
}

TEST(SnapAndShrink, SnapRespectsTheHeightLimit) {
  // Regression (kitten at --max-height 0.05 gave a block taller than the
  // limit): the same two tops as above, but with a height limit of 2.1 the
  // lower top may not be raised to 2.25; the higher one is lowered instead.
  const Mesh mesh = test::union_of_boxes({{{0, 0, 0}, {10, 1, 2}}});
  const std::vector<HeightBox> boxes = {hb({0, 0, 0}, {6, 1, 2}, Axis::PosZ), hb({4, 0, 0}, {10, 1, 2.25}, Axis::PosZ)};
  SnapShrinkOptions options;
  options.snap_distance = 0.5;
  options.shrink = false;
  options.max_height = 2.1;
  const SnapShrinkResult r = snap_and_shrink(mesh, boxes, options);
  EXPECT_EQ(r.boxes[0].box.max.z(), r.boxes[1].box.max.z());
  for (const HeightBox& b : r.boxes) EXPECT_LE(b.box.max.z() - b.box.min.z(), 2.1);
  expect_valid_and_covering(mesh, boxes, r.boxes);
}

TEST(SnapAndShrink, NoSnapBeyondTheDistance) {
  const std::vector<HeightBox> boxes = {hb({0, 0, 0}, {4, 1, 1}, Axis::PosZ), hb({5, 0, 0}, {10, 1, 1}, Axis::PosZ)};
  SnapShrinkOptions options;
  options.snap_distance = 0.5;
  const SnapShrinkResult r = snap_and_shrink(bar(), boxes, options);
  EXPECT_EQ(r.num_snapped, 0);
  EXPECT_EQ(r.boxes[0].box.max.x(), 4.0);
}

TEST(SnapAndShrink, SnapNeverMakesABoxInvalid) {
  // An overhang: solid [0,10]x[0,1]x[0,1] plus a shelf [4,10]x[0,1]x[2,3]
  // held by a wall [9,10]x[0,1]x[1,2]. The +z box [0,4]x[0,1]x[0,3] cannot
  // grow onto the box starting at x = 4.25: it would swallow the shelf's
  // underside (facing -z). The other box grows instead.
  const Mesh mesh = test::union_of_boxes({{{0, 0, 0}, {10, 1, 1}}, {{9, 0, 1}, {10, 1, 2}}, {{4, 0, 2}, {10, 1, 3}}});
  const std::vector<HeightBox> boxes = {hb({0, 0, 0}, {4, 1, 3}, Axis::PosZ), hb({4.25, 0, 0}, {9, 1, 1}, Axis::PosZ),
                                        hb({4, 0, 2}, {10, 1, 3}, Axis::PosZ), hb({9, 0, 0}, {10, 1, 3}, Axis::PosX)};
  const detail::SolidIndex index(mesh);
  for (const HeightBox& b : boxes) ASSERT_TRUE(index.box_is_valid(b));
  SnapShrinkOptions options;
  options.snap_distance = 0.5;
  options.shrink = false;
  const SnapShrinkResult r = snap_and_shrink(mesh, boxes, options);
  EXPECT_EQ(r.num_snapped, 1);
  EXPECT_EQ(r.boxes[0].box.max.x(), 4.0);
  EXPECT_EQ(r.boxes[1].box.min.x(), 4.0);
  expect_valid_and_covering(mesh, boxes, r.boxes);
}

TEST(SnapAndShrink, ShrinkRemovesAnOverlapWhenCoverageAllows) {
  const std::vector<HeightBox> boxes = {hb({0, 0, 0}, {6, 1, 1}, Axis::PosZ), hb({4, 0, 0}, {10, 1, 1}, Axis::PosZ)};
  SnapShrinkOptions options;
  options.snap_distance = 0;
  const SnapShrinkResult r = snap_and_shrink(bar(), boxes, options);
  EXPECT_EQ(r.num_snapped, 0);
  EXPECT_EQ(r.num_shrunk, 1);
  EXPECT_FALSE(r.boxes[0].box.overlaps(r.boxes[1].box));
  expect_valid_and_covering(bar(), boxes, r.boxes);
}

TEST(SnapAndShrink, ShrinkKeepsAnOverlapThatCoverageNeeds) {
  // Faces [3,4] lie only in the left box and faces [6,7] only in the right
  // one: neither can give up the overlap [3.5, 6.5].
  const std::vector<HeightBox> boxes = {hb({0, 0, 0}, {6.5, 1, 1}, Axis::PosZ), hb({3.5, 0, 0}, {10, 1, 1}, Axis::PosZ)};
  SnapShrinkOptions options;
  options.snap_distance = 0;
  const SnapShrinkResult r = snap_and_shrink(bar(), boxes, options);
  EXPECT_EQ(r.num_shrunk, 0);
  EXPECT_EQ(r.boxes[0].box.max, boxes[0].box.max);
  EXPECT_EQ(r.boxes[1].box.min, boxes[1].box.min);
}

TEST(SnapAndShrink, RejectsInvalidInput) {
  EXPECT_THROW(snap_and_shrink(bar(), {hb({0, 0, -1}, {10, 1, 2}, Axis::PosZ)}, {}), InvalidArgumentError);
  SnapShrinkOptions bad;
  bad.max_shrink_passes = -1;
  EXPECT_THROW(snap_and_shrink(bar(), {}, bad), InvalidArgumentError);
}

TEST(SnapAndShrink, RandomBoxesStayValidAndCovering) {
  const Mesh mesh = test::union_of_boxes({{{0, 0, 0}, {6, 6, 6}}, {{2, 2, 6}, {4, 4, 7}}, {{6, 1, 1}, {7, 3, 3}}});
  const detail::SolidIndex index(mesh);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(-0.5, 7.5);
  std::uniform_int_distribution<int> axis(0, 5);
  std::vector<HeightBox> boxes;
  while (boxes.size() < 25) {
    Vec3 lo(coord(rng), coord(rng), coord(rng)), hi(coord(rng), coord(rng), coord(rng));
    const Vec3 a = lo.cwiseMin(hi), b = lo.cwiseMax(hi);
    const HeightBox box = hb(a, b, static_cast<Axis>(axis(rng)));
    if (box.box.volume() > 0 && index.box_is_valid(box) && !index.faces_covered(box).empty()) boxes.push_back(box);
  }
  const SnapShrinkResult r = snap_and_shrink(mesh, boxes, {});
  expect_valid_and_covering(mesh, boxes, r.boxes);
  EXPECT_GT(r.num_snapped + r.num_shrunk, 0);
  EXPECT_LE(num_overlapping_pairs(r.boxes), num_overlapping_pairs(boxes) + static_cast<std::size_t>(r.num_snapped));
  const SnapShrinkResult again = snap_and_shrink(mesh, boxes, {});
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    EXPECT_EQ(r.boxes[i].box.min, again.boxes[i].box.min);
    EXPECT_EQ(r.boxes[i].box.max, again.boxes[i].box.max);
  }
}

}  // namespace
}  // namespace subfab
