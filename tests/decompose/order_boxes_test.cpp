// SPDX-License-Identifier: GPL-3.0-or-later
// The graph part of overlap resolution, with synthetic geometry: the solid
// fills all of space, so carving `first` before `second` is invalid exactly
// when conflict_region() and conflict_support() are not empty.
#include "decompose/order_boxes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "subfab/core/error.h"

namespace subfab::detail {
namespace {

Box3 make_box(double x0, double y0, double z0, double x1, double y1, double z1) {
  return Box3{Vec3(x0, y0, z0), Vec3(x1, y1, z1)};
}

HeightBox hb(const Box3& b, Axis a) { return HeightBox{b, a, -1}; }

BoxOrderCallbacks full_space_callbacks() {
  BoxOrderCallbacks cb;
  cb.conflict = [](const HeightBox& a, const HeightBox& b) {
    return conflict_region(a, b).has_value() && !conflict_support(a, b).empty();
  };
  cb.size = [](const HeightBox& b) { return b.box.volume(); };
  return cb;
}

bool in_some_box(const Vec3& p, const std::vector<HeightBox>& boxes) {
  return std::any_of(boxes.begin(), boxes.end(), [&](const HeightBox& b) { return b.box.contains(p); });
}

//! Property of a resolved order: no later box is invalidated by an earlier one.
void expect_valid_order(const std::vector<HeightBox>& ordered, const BoxOrderCallbacks& cb) {
  for (std::size_t i = 0; i < ordered.size(); ++i)
    for (std::size_t j = i + 1; j < ordered.size(); ++j)
      EXPECT_FALSE(cb.conflict(ordered[i], ordered[j])) << "box " << i << " carved before box " << j;
}

//! Points of the input union stay in the output union (grid samples).
void expect_same_union(const std::vector<HeightBox>& in, const std::vector<HeightBox>& out, int samples_per_axis) {
  Box3 all = in.front().box;
  for (const HeightBox& b : in) {
    all.min = all.min.cwiseMin(b.box.min);
    all.max = all.max.cwiseMax(b.box.max);
  }
  for (int i = 0; i <= samples_per_axis; ++i)
    for (int j = 0; j <= samples_per_axis; ++j)
      for (int k = 0; k <= samples_per_axis; ++k) {
        const Vec3 t(i, j, k);
        const Vec3 p = all.min + (all.max - all.min).cwiseProduct(t / samples_per_axis);
        EXPECT_EQ(in_some_box(p, in), in_some_box(p, out)) << p.transpose();
      }
}

TEST(ConflictRegion, DependsOnTheSecondBoxDirection) {
  const HeightBox tall = hb(make_box(0, 0, 0, 2, 2, 2), Axis::PosZ);
  const HeightBox low = hb(make_box(1, 0, 0, 3, 2, 1), Axis::PosZ);
  EXPECT_FALSE(conflict_region(tall, low));  // tall's top is above low's top
  const auto region = conflict_region(low, tall);
  ASSERT_TRUE(region);  // low's top at z = 1 cuts tall between its base and top
  EXPECT_EQ(region->min, Vec3(1, 0, 1));
  EXPECT_EQ(region->max, Vec3(2, 2, 2));
  // Milled from below (-z): the face of `low` at z = 0 is its top for -z.
  const HeightBox down = hb(make_box(1, 0, -1, 3, 2, 1), Axis::NegZ);
  const auto below = conflict_region(tall, down);
  ASSERT_TRUE(below);  // tall's bottom z = 0 lies strictly inside down's (-1, 1)
  EXPECT_EQ(below->min, Vec3(1, 0, -1));
  EXPECT_EQ(below->max, Vec3(2, 2, 0));
  // Support: the part of `tall` below z = 1 outside `low`.
  const std::vector<Box3> support = conflict_support(low, tall);
  ASSERT_EQ(support.size(), 1u);
  EXPECT_EQ(support[0].min, Vec3(0, 0, 0));
  EXPECT_EQ(support[0].max, Vec3(1, 2, 1));
  // A box whose lower part lies inside the first box: its remainder sits on
  // the first box's top, which becomes its base (no conflict in full space).
  const HeightBox bar = hb(make_box(0, 0, 0, 3, 1, 1), Axis::PosZ);
  const HeightBox column = hb(make_box(0, 0, 0, 1, 1, 3), Axis::PosZ);
  EXPECT_TRUE(conflict_region(bar, column));
  EXPECT_TRUE(conflict_support(bar, column).empty());
  // Touching boxes never conflict.
  EXPECT_FALSE(conflict_region(hb(make_box(0, 0, 0, 1, 1, 1), Axis::PosZ), hb(make_box(1, 0, 0, 2, 1, 2), Axis::PosZ)));
}

TEST(BoxDifference, PartitionsTheRemainder) {
  const Box3 b = make_box(0, 0, 0, 4, 4, 4);
  const Box3 cut = make_box(1, 1, 1, 2, 5, 3);
  for (const std::array<int, 3> dims : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{2, 1, 0}}) {
    const std::vector<Box3> pieces = box_difference(b, cut, dims);
    double volume = 0;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      EXPECT_GT(pieces[i].volume(), 0.0);
      EXPECT_TRUE(b.contains(pieces[i].min) && b.contains(pieces[i].max));
      EXPECT_FALSE(pieces[i].overlaps(cut));
      for (std::size_t j = i + 1; j < pieces.size(); ++j) EXPECT_FALSE(pieces[i].overlaps(pieces[j]));
      volume += pieces[i].volume();
    }
    EXPECT_DOUBLE_EQ(volume, 64.0 - 1.0 * 3.0 * 2.0);
    EXPECT_EQ(pieces.size(), 5u);  // cut reaches out of b on one side (+y)
  }
  EXPECT_TRUE(box_difference(b, make_box(-1, -1, -1, 5, 5, 5), {0, 1, 2}).empty());
  EXPECT_EQ(box_difference(b, make_box(4, 0, 0, 5, 1, 1), {0, 1, 2}).size(), 1u);
}

TEST(StronglyConnectedComponents, FindsCyclesOnly) {
  // 0 -> 1 -> 2 -> 0, 2 -> 3, 3 -> 4 -> 3, 5 alone, 6 dead (in a cycle with 5).
  const std::vector<std::vector<int>> out = {{1}, {2}, {0, 3}, {4}, {3}, {6}, {5}};
  const std::vector<char> alive = {1, 1, 1, 1, 1, 1, 0};
  const std::vector<int> comp = strongly_connected_components(out, alive);
  EXPECT_EQ(comp[0], comp[1]);
  EXPECT_EQ(comp[1], comp[2]);
  EXPECT_EQ(comp[3], comp[4]);
  EXPECT_NE(comp[0], comp[3]);
  EXPECT_NE(comp[5], comp[0]);
  EXPECT_NE(comp[5], comp[3]);
  EXPECT_EQ(comp[6], -1);
}

TEST(OrderBoxes, CompatibleOverlapNeedsNoSplit) {
  // Same height, same direction: neither difference has a new top face.
  const std::vector<HeightBox> boxes = {hb(make_box(0, 0, 0, 2, 2, 1), Axis::PosZ),
                                        hb(make_box(1, 0, 0, 3, 3, 1), Axis::PosZ)};
  const auto cb = full_space_callbacks();
  const BoxOrderResult r = order_boxes(boxes, cb, {});
  EXPECT_EQ(r.num_initial_edges, 0u);
  EXPECT_EQ(r.num_splits, 0);
  ASSERT_EQ(r.ordered.size(), 2u);
  EXPECT_EQ(r.ordered[0].box.max, Vec3(2, 2, 1));  // the smaller block first
}

TEST(OrderBoxes, OneWayConflictOrdersTheBoxes) {
  // low -> tall (tall minus low is invalid): tall must be carved first, even
  // though low is smaller.
  const HeightBox tall = hb(make_box(0, 0, 0, 2, 2, 2), Axis::PosZ);
  const HeightBox low = hb(make_box(1, 0, 0, 3, 2, 1), Axis::PosZ);
  const auto cb = full_space_callbacks();
  const BoxOrderResult r = order_boxes({low, tall}, cb, {});
  EXPECT_EQ(r.num_initial_edges, 1u);
  EXPECT_EQ(r.num_splits, 0);
  ASSERT_EQ(r.ordered.size(), 2u);
  EXPECT_EQ(r.ordered[0].box.max, tall.box.max);
  expect_valid_order(r.ordered, cb);
}

std::vector<HeightBox> plus_pair() {
  // Figure 4.5c: a +z box and a +x box crossing like a plus sign; each
  // difference has material below the other box's face.
  return {hb(make_box(0, 0, 1, 3, 1, 4), Axis::PosZ), hb(make_box(1, 0, 0, 5, 1, 2), Axis::PosX)};
}

TEST(OrderBoxes, TwoCycleOfFigure4_5cIsSplit) {
  const std::vector<HeightBox> boxes = plus_pair();
  const auto cb = full_space_callbacks();
  EXPECT_TRUE(cb.conflict(boxes[0], boxes[1]));
  EXPECT_TRUE(cb.conflict(boxes[1], boxes[0]));
  const BoxOrderResult r = order_boxes(boxes, cb, {});
  EXPECT_EQ(r.num_initial_edges, 2u);
  EXPECT_EQ(r.num_initial_cyclic, 2u);
  EXPECT_EQ(r.num_splits, 1);
  EXPECT_GE(r.ordered.size(), 2u);
  expect_valid_order(r.ordered, cb);
  expect_same_union(boxes, r.ordered, 8);
}

TEST(OrderBoxes, ThreeCycleIsSplit) {
  // A -> B -> C -> A and no reverse edges.
  const HeightBox a = hb(make_box(0, 2, 2, 3, 3, 5), Axis::PosX);
  const HeightBox b = hb(make_box(1, 2, 0, 3, 4, 3), Axis::PosY);
  const HeightBox c = hb(make_box(0, 2, 2, 2, 4, 4), Axis::PosZ);
  const auto cb = full_space_callbacks();
  ASSERT_TRUE(cb.conflict(a, b) && cb.conflict(b, c) && cb.conflict(c, a));
  ASSERT_FALSE(cb.conflict(b, a) || cb.conflict(c, b) || cb.conflict(a, c));
  const BoxOrderResult r = order_boxes({a, b, c}, cb, {});
  EXPECT_EQ(r.num_initial_edges, 3u);
  EXPECT_EQ(r.num_initial_cyclic, 3u);
  EXPECT_GE(r.num_splits, 1);
  expect_valid_order(r.ordered, cb);
  expect_same_union({a, b, c}, r.ordered, 6);
}

TEST(OrderBoxes, SmallestRootsFirst) {
  const std::vector<HeightBox> boxes = {hb(make_box(0, 0, 0, 3, 3, 3), Axis::PosZ),
                                        hb(make_box(10, 0, 0, 11, 1, 1), Axis::PosX),
                                        hb(make_box(20, 0, 0, 22, 2, 2), Axis::NegY)};
  const BoxOrderResult r = order_boxes(boxes, full_space_callbacks(), {});
  ASSERT_EQ(r.ordered.size(), 3u);
  EXPECT_EQ(r.ordered[0].axis, Axis::PosX);
  EXPECT_EQ(r.ordered[1].axis, Axis::NegY);
  EXPECT_EQ(r.ordered[2].axis, Axis::PosZ);
}

TEST(OrderBoxes, DroppablePiecesAreLeftOut) {
  const std::vector<HeightBox> boxes = plus_pair();
  auto cb = full_space_callbacks();
  cb.droppable = [](const HeightBox&, const HeightBox&) { return true; };  // every piece
  int num_replaced = 0;
  cb.replaced = [&](const HeightBox&, const std::vector<HeightBox>& kept) {
    ++num_replaced;
    EXPECT_TRUE(kept.empty());
  };
  const BoxOrderResult r = order_boxes(boxes, cb, {});
  EXPECT_EQ(r.num_splits, 1);
  EXPECT_GE(r.num_dropped_pieces, 1);
  EXPECT_EQ(r.ordered.size(), 1u);  // the split box vanished entirely
  EXPECT_EQ(num_replaced, 1);
}

TEST(OrderBoxes, RandomBoxesGiveAValidDeterministicOrder) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> coord(0, 12), extent(1, 6), axis(0, 5);
  std::vector<HeightBox> boxes;
  for (int i = 0; i < 25; ++i) {
    const Vec3 lo(coord(rng), coord(rng), coord(rng));
    const Vec3 ext(extent(rng), extent(rng), extent(rng));
    boxes.push_back(hb(Box3{lo, lo + ext}, static_cast<Axis>(axis(rng))));
  }
  const auto cb = full_space_callbacks();
  const BoxOrderResult r1 = order_boxes(boxes, cb, {});
  const BoxOrderResult r2 = order_boxes(boxes, cb, {});
  ASSERT_EQ(r1.ordered.size(), r2.ordered.size());
  for (std::size_t i = 0; i < r1.ordered.size(); ++i) {
    EXPECT_EQ(r1.ordered[i].box.min, r2.ordered[i].box.min);
    EXPECT_EQ(r1.ordered[i].box.max, r2.ordered[i].box.max);
    EXPECT_EQ(r1.ordered[i].axis, r2.ordered[i].axis);
  }
  EXPECT_GT(r1.num_initial_cyclic, 0u);  // the instance really has cycles
  expect_valid_order(r1.ordered, cb);
  expect_same_union(boxes, r1.ordered, 18);
}

TEST(OrderBoxes, SplitLimitIsAnError) {
  const std::vector<HeightBox> boxes = plus_pair();
  BoxOrderOptions options;
  options.max_splits = 0;
  EXPECT_THROW(order_boxes(boxes, full_space_callbacks(), options), AlgorithmError);
}

}  // namespace
}  // namespace subfab::detail
