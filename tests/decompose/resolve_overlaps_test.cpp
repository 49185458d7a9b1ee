// SPDX-License-Identifier: GPL-3.0-or-later
// Overlap resolution on voxel solids (unions of integer boxes), where a
// brute-force voxel check decides exactly whether a carved block is a height
// field: the exact conflict test must agree with it, and the carve order
// must give valid blocks when the boxes are carved one after the other.
#include "subfab/decompose/resolve_overlaps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <random>
#include <set>
#include <string>

#include "support/block_test_shapes.h"
#include "decompose/resolve_overlaps_detail.h"
#include "geometry/solid_index.h"
#include "support/voxel_solid.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

using test::Cell;
using CellSet = std::set<Cell>;

HeightBox hb(const Cell& lo, const Cell& hi, Axis axis) {
  return HeightBox{Box3{Vec3(lo[0], lo[1], lo[2]), Vec3(hi[0], hi[1], hi[2])}, axis, -1};
}

CellSet cells_in(const Box3& b) {
  // Boxes in these tests have integer corners.
  return test::cells_of_box({static_cast<int>(b.min.x()), static_cast<int>(b.min.y()), static_cast<int>(b.min.z())},
                            {static_cast<int>(b.max.x()), static_cast<int>(b.max.y()), static_cast<int>(b.max.z())});
}

//! Brute force: is the voxel set a height-field block along `axis` (every
//! cell whose neighbour towards -d is missing lies on the lowest level)?
bool voxel_block_valid(const CellSet& block, Axis axis) {
  if (block.empty()) return true;
  const auto k = static_cast<std::size_t>(axis_dimension(axis));
  const int s = axis_sign(axis);
  auto level = [&](const Cell& c) { return s > 0 ? c[k] : -(c[k] + 1); };
  int lowest = level(*block.begin());
  for (const Cell& c : block) lowest = std::min(lowest, level(c));
  for (const Cell& c : block) {
    Cell below = c;
    below[k] -= s;
    if (!block.count(below) && level(c) != lowest) return false;
  }
  return true;
}

//! Brute force: carve the boxes in order from the solid; all blocks valid?
bool voxel_carve_valid(const CellSet& solid, const std::vector<HeightBox>& ordered, std::string* why) {
  CellSet remaining = solid;
  for (std::size_t i = 0; i < ordered.size(); ++i) {
    CellSet block;
    for (const Cell& c : cells_in(ordered[i].box))
      if (remaining.erase(c)) block.insert(c);
    if (!voxel_block_valid(block, ordered[i].axis)) {
      *why = "block " + std::to_string(i) + " is not a height field";
      return false;
    }
  }
  return true;
}

CellSet minus(const CellSet& a, const CellSet& b) {
  CellSet out;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::inserter(out, out.end()));
  return out;
}
CellSet intersect(const CellSet& a, const CellSet& b) {
  CellSet out;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::inserter(out, out.end()));
  return out;
}

//! The exact test must say "conflict" exactly when the voxel block of
//! second minus first is not a height field.
void expect_conflict_matches_voxels(const detail::SolidIndex& index, const CellSet& solid, const HeightBox& first,
                                    const HeightBox& second) {
  const CellSet block = minus(intersect(solid, cells_in(second.box)), cells_in(first.box));
  EXPECT_EQ(detail::carving_conflict(index, first, second), !voxel_block_valid(block, second.axis))
      << "first " << first.box.min.transpose() << " / " << first.box.max.transpose() << " axis "
      << axis_name(first.axis) << ", second " << second.box.min.transpose() << " / " << second.box.max.transpose()
      << " axis " << axis_name(second.axis);
}

//! Solid next to each face (just inside it) that some input box held is
//! still held by an output box, at a grid of points over every face (a face
//! can be held by several boxes together and by none alone).
void expect_coverage_kept(const Mesh& mesh, const std::vector<HeightBox>& in, const std::vector<HeightBox>& out) {
  auto held = [](const Vec3& p, const std::vector<HeightBox>& boxes) {
    return std::any_of(boxes.begin(), boxes.end(), [&](const HeightBox& b) { return b.box.contains(p); });
  };
  constexpr int kSteps = 12;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Triangle& t = mesh.faces[f];
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    const Vec3 inward = -1e-3 * face_unit_normal(mesh, f);
    for (int i = 0; i < kSteps; ++i)
      for (int j = 0; i + j < kSteps; ++j) {
        const double u = (i + 1.0 / 3) / kSteps, v = (j + 1.0 / 3) / kSteps;
        const Vec3 p = a + u * (b - a) + v * (c - a) + inward;
        if (held(p, in)) {
          EXPECT_TRUE(held(p, out)) << "face " << f << " at " << p.transpose();
        }
      }
  }
}

struct Case {
  CellSet solid;
  Mesh mesh;
  std::vector<HeightBox> boxes;
};

Case make_case(const std::vector<std::pair<Cell, Cell>>& parts, std::vector<HeightBox> boxes) {
  Case c;
  for (const auto& [lo, hi] : parts) c.solid.merge(test::cells_of_box(lo, hi));
  c.mesh = test::voxel_mesh(c.solid);
  c.boxes = std::move(boxes);
  return c;
}

//! Runs resolve and checks every property; returns the result.
ResolveResult resolve_and_check(const Case& c) {
  const detail::SolidIndex index(c.mesh);
  for (const HeightBox& b : c.boxes) EXPECT_TRUE(index.box_is_valid(b)) << "test setup: invalid box";
  for (const HeightBox& a : c.boxes)
    for (const HeightBox& b : c.boxes)
      if (&a != &b) expect_conflict_matches_voxels(index, c.solid, a, b);
  const ResolveResult r = resolve_overlaps(c.mesh, c.boxes, {});
  for (std::size_t i = 0; i < r.ordered.size(); ++i) {
    EXPECT_TRUE(index.box_is_valid(r.ordered[i]));
    for (std::size_t j = i + 1; j < r.ordered.size(); ++j)
      EXPECT_FALSE(detail::carving_conflict(index, r.ordered[i], r.ordered[j])) << i << " before " << j;
  }
  std::string why;
  EXPECT_TRUE(voxel_carve_valid(c.solid, r.ordered, &why)) << why;
  expect_coverage_kept(c.mesh, c.boxes, r.ordered);
  return r;
}

TEST(ResolveOverlaps, CompatibleOverlapHasNoEdge) {
  const Case c = make_case({{{0, 0, 0}, {3, 1, 1}}},
                           {hb({0, 0, 0}, {2, 1, 1}, Axis::PosZ), hb({1, 0, 0}, {3, 1, 1}, Axis::PosZ)});
  const ResolveResult r = resolve_and_check(c);
  EXPECT_EQ(r.num_conflict_edges, 0u);
  EXPECT_EQ(r.num_splits, 0);
  EXPECT_EQ(r.ordered.size(), 2u);
}

TEST(ResolveOverlaps, LShapeColumnSitsOnTheBar) {
  // Bar along x and a column on its left end, both milled from +z. Carving
  // the bar first leaves the column's upper part, whose base is the bar's
  // top: valid, so no edge although the boxes overlap.
  const Case c = make_case({{{0, 0, 0}, {3, 1, 1}}, {{0, 0, 0}, {1, 1, 3}}},
                           {hb({0, 0, 0}, {3, 1, 1}, Axis::PosZ), hb({0, 0, 0}, {1, 1, 3}, Axis::PosZ)});
  const ResolveResult r = resolve_and_check(c);
  EXPECT_EQ(r.num_conflict_edges, 0u);
  EXPECT_EQ(r.ordered.size(), 2u);
}

TEST(ResolveOverlaps, StepNeedsTheTallBoxFirst) {
  // A tall part [0,2]x[0,2] and a low step [1,3]x[0,1] (xz), both +z.
  // Carving the low box first would leave the tall block with two floors.
  const HeightBox tall = hb({0, 0, 0}, {2, 1, 2}, Axis::PosZ);
  const HeightBox low = hb({1, 0, 0}, {3, 1, 1}, Axis::PosZ);
  const Case c = make_case({{{0, 0, 0}, {2, 1, 2}}, {{1, 0, 0}, {3, 1, 1}}}, {low, tall});
  const ResolveResult r = resolve_and_check(c);
  EXPECT_EQ(r.num_conflict_edges, 1u);
  EXPECT_EQ(r.num_splits, 0);
  ASSERT_EQ(r.ordered.size(), 2u);
  EXPECT_EQ(r.ordered[0].box.max, tall.box.max);
}

TEST(ResolveOverlaps, TShape) {
  // Bar [0,3]x[2,3] (xz) milled from +z over a stem [1,2]x[0,2] milled from
  // -z (overlapping the bar), and the same stem box milled from +z.
  const std::vector<std::pair<Cell, Cell>> t = {{{0, 0, 2}, {3, 1, 3}}, {{1, 0, 0}, {2, 1, 2}}};
  const Case down = make_case(t, {hb({0, 0, 2}, {3, 1, 3}, Axis::PosZ), hb({1, 0, 0}, {2, 1, 3}, Axis::NegZ)});
  const ResolveResult r1 = resolve_and_check(down);
  EXPECT_EQ(r1.num_splits, 0);
  const Case up = make_case(t, {hb({0, 0, 2}, {3, 1, 3}, Axis::PosZ), hb({1, 0, 0}, {2, 1, 3}, Axis::PosZ)});
  const ResolveResult r2 = resolve_and_check(up);
  EXPECT_EQ(r2.num_splits, 0);
}

TEST(ResolveOverlaps, CrossingBoxesOfFigure4_5cAreSplit) {
  // A +z box and a +x box crossing like a plus sign: both orders are invalid.
  const HeightBox a = hb({0, 0, 1}, {3, 1, 4}, Axis::PosZ);
  const HeightBox b = hb({1, 0, 0}, {5, 1, 2}, Axis::PosX);
  const Case c = make_case({{{0, 0, 1}, {3, 1, 4}}, {{1, 0, 0}, {5, 1, 2}}}, {a, b});
  const detail::SolidIndex index(c.mesh);
  EXPECT_TRUE(detail::carving_conflict(index, a, b));
  EXPECT_TRUE(detail::carving_conflict(index, b, a));
  const ResolveResult r = resolve_and_check(c);
  EXPECT_EQ(r.num_conflict_edges, 2u);
  EXPECT_EQ(r.num_boxes_on_cycles, 2u);
  EXPECT_EQ(r.num_splits, 1);
  EXPECT_GE(r.ordered.size(), 3u);
}

TEST(ResolveOverlaps, CycleIsBrokenByATrimWhenAnotherBoxKeepsTheSurface) {
  // The crossing boxes of Figure 4.5c, plus a +z box holding the upper right
  // part of the +z arm: the +z box can give up x > 1 (its faces there are
  // held by the other two), which removes the overlap: no split, no new box.
  const HeightBox a = hb({0, 0, 1}, {3, 1, 4}, Axis::PosZ);
  const HeightBox b = hb({1, 0, 0}, {5, 1, 2}, Axis::PosX);
  const HeightBox c3 = hb({1, 0, 2}, {3, 1, 4}, Axis::PosZ);
  const Case c = make_case({{{0, 0, 1}, {3, 1, 4}}, {{1, 0, 0}, {5, 1, 2}}}, {a, b, c3});
  const detail::SolidIndex index(c.mesh);
  EXPECT_TRUE(detail::carving_conflict(index, a, b));
  EXPECT_TRUE(detail::carving_conflict(index, b, a));
  const ResolveResult r = resolve_and_check(c);
  EXPECT_EQ(r.num_boxes_on_cycles, 2u);
  EXPECT_EQ(r.num_splits, 0);
  EXPECT_EQ(r.num_trims, 1);
  ASSERT_EQ(r.ordered.size(), 3u);
  const auto trimmed = std::find_if(r.ordered.begin(), r.ordered.end(), [](const HeightBox& h) {
    return h.axis == Axis::PosZ && h.box.min == Vec3(0, 0, 1);
  });
  ASSERT_NE(trimmed, r.ordered.end());
  EXPECT_EQ(trimmed->box.max, Vec3(1, 1, 4));
}

TEST(ResolveOverlaps, NoTrimThatLosesSurface) {
  // Without the third box every trim of the cross loses faces: a split.
  const HeightBox a = hb({0, 0, 1}, {3, 1, 4}, Axis::PosZ);
  const HeightBox b = hb({1, 0, 0}, {5, 1, 2}, Axis::PosX);
  const Case c = make_case({{{0, 0, 1}, {3, 1, 4}}, {{1, 0, 0}, {5, 1, 2}}}, {a, b});
  const detail::SolidIndex index(c.mesh);
  std::vector<int> count(static_cast<std::size_t>(index.num_faces()), 0);
  for (const HeightBox& h : {a, b})
    for (int f : index.faces_covered(h)) ++count[static_cast<std::size_t>(f)];
  const auto size = [](const HeightBox& h) { return h.box.volume(); };
  const auto keeps = [&](const HeightBox& old_box, const HeightBox& trimmed) {
    const std::vector<int> before = index.faces_covered(old_box), after = index.faces_covered(trimmed);
    std::vector<int> lost;
    std::set_difference(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(lost));
    return std::all_of(lost.begin(), lost.end(), [&](int f) { return count[static_cast<std::size_t>(f)] >= 2; });
  };
  EXPECT_TRUE(detail::conflict_trims(index, a, b, size, keeps).empty());
  EXPECT_TRUE(detail::conflict_trims(index, b, a, size, keeps).empty());
  // Every face may go: trims exist, each breaks its edge exactly.
  const auto all = [](const HeightBox&, const HeightBox&) { return true; };
  const std::vector<detail::BoxTrim> trims = detail::conflict_trims(index, a, b, size, all);
  EXPECT_FALSE(trims.empty());
  for (const detail::BoxTrim& t : trims) {
    const HeightBox moved{t.box, t.which == 0 ? a.axis : b.axis, -1};
    EXPECT_FALSE(t.which == 0 ? detail::carving_conflict(index, moved, b) : detail::carving_conflict(index, a, moved));
    EXPECT_GT(t.removed, 0);
  }
}

TEST(ResolveOverlaps, TrimKeepsSurfaceThatOnlyTheBoxesTogetherHold) {
  // Regression (bunny_lowres failed the coverage check: after cycle splits a
  // triangle can be held by several boxes together and by none alone, and a
  // trim that only checked the faces the box held alone gave up the part of
  // such a triangle no other box held). Cube [0,2]^3 of 12 triangles, each a
  // half side: no box holds one alone. A (+x) and B (+z) cross as in Figure
  // 4.5c (a 2-cycle), C and D fill the two corners they leave. Moving A's
  // x-min face from 0.5 to 1 breaks the cycle with the least volume, but
  // [0.5,1] x [0,2] x [0,0.5] holds bottom and side surface only A holds.
  const Mesh cube = test::box_solid(Vec3(0, 0, 0), Vec3(2, 2, 2));
  const HeightBox a = hb({1, 0, 0}, {4, 4, 2}, Axis::PosX);
  const HeightBox b = hb({0, 0, 1}, {2, 4, 4}, Axis::PosZ);
  const HeightBox c = hb({0, 0, 0}, {1, 4, 1}, Axis::PosZ);
  const HeightBox d = hb({2, 0, 2}, {4, 4, 4}, Axis::PosZ);
  std::vector<HeightBox> boxes;
  for (HeightBox h : {a, b, c, d}) {
    h.box.min *= 0.5;
    h.box.max *= 0.5;
    boxes.push_back(h);
  }
  const detail::SolidIndex index(cube);
  EXPECT_TRUE(detail::carving_conflict(index, boxes[0], boxes[1]));
  EXPECT_TRUE(detail::carving_conflict(index, boxes[1], boxes[0]));
  const ResolveResult r = resolve_overlaps(cube, boxes, {});
  EXPECT_EQ(r.num_boxes_on_cycles, 2u);
  for (std::size_t i = 0; i < r.ordered.size(); ++i) {
    EXPECT_TRUE(index.box_is_valid(r.ordered[i]));
    for (std::size_t j = i + 1; j < r.ordered.size(); ++j)
      EXPECT_FALSE(detail::carving_conflict(index, r.ordered[i], r.ordered[j])) << i << " before " << j;
  }
  expect_coverage_kept(cube, boxes, r.ordered);
}

TEST(ResolveOverlaps, ThreeCycleIsBroken) {
  const HeightBox a = hb({0, 2, 2}, {3, 3, 5}, Axis::PosX);
  const HeightBox b = hb({1, 2, 0}, {3, 4, 3}, Axis::PosY);
  const HeightBox c3 = hb({0, 2, 2}, {2, 4, 4}, Axis::PosZ);
  const Case c = make_case({{{0, 2, 2}, {3, 3, 5}}, {{1, 2, 0}, {3, 4, 3}}, {{0, 2, 2}, {2, 4, 4}}}, {a, b, c3});
  const detail::SolidIndex index(c.mesh);
  EXPECT_TRUE(detail::carving_conflict(index, a, b));
  EXPECT_TRUE(detail::carving_conflict(index, b, c3));
  EXPECT_TRUE(detail::carving_conflict(index, c3, a));
  EXPECT_FALSE(detail::carving_conflict(index, b, a));
  EXPECT_FALSE(detail::carving_conflict(index, c3, b));
  EXPECT_FALSE(detail::carving_conflict(index, a, c3));
  const ResolveResult r = resolve_and_check(c);
  EXPECT_EQ(r.num_boxes_on_cycles, 3u);
  EXPECT_GE(r.num_splits + r.num_trims, 1);  // broken by a split or by a trim that loses no surface
}

TEST(ResolveOverlaps, EmptyPiecesAreDropped) {
  // The +x box of the cross sticks out of the solid on +y: after the split,
  // the piece beyond y = 1 holds no solid and is left out.
  const HeightBox a = hb({0, 0, 1}, {3, 1, 4}, Axis::PosZ);
  const HeightBox b = hb({1, 0, 0}, {5, 2, 2}, Axis::PosX);
  const Case c = make_case({{{0, 0, 1}, {3, 1, 4}}, {{1, 0, 0}, {5, 1, 2}}}, {a, b});
  const ResolveResult r = resolve_and_check(c);
  EXPECT_EQ(r.num_splits, 1);
  const detail::SolidIndex index(c.mesh);
  for (const HeightBox& box : r.ordered)  // no output box is empty
    EXPECT_TRUE(!index.faces_meeting_open_box(box.box).empty() || index.is_inside(box.box.min));
}

TEST(ResolveOverlaps, RejectsInvalidBoxes) {
  const Case c = make_case({{{0, 0, 0}, {2, 1, 2}}, {{1, 0, 0}, {3, 1, 1}}}, {});
  // Milled from -z, the step's top at z = 1 faces away (+z) inside this box.
  EXPECT_THROW(resolve_overlaps(c.mesh, {hb({0, 0, 0}, {3, 1, 2}, Axis::NegZ)}, {}), InvalidArgumentError);
}

TEST(ResolveOverlaps, RandomValidBoxesAgreeWithVoxelsAndAreDeterministic) {
  // Bars (few conflicts) and a cube with bumps (boxes inside the cube are
  // all valid and cross each other: cycles); random valid boxes over them.
  const std::vector<std::pair<Cell, Cell>> bars = {{{0, 0, 0}, {6, 2, 2}}, {{0, 0, 0}, {2, 6, 2}},
                                                   {{0, 0, 0}, {2, 2, 6}}, {{3, 0, 2}, {5, 2, 4}},
                                                   {{0, 3, 2}, {2, 5, 5}}};
  const std::vector<std::pair<Cell, Cell>> bumpy_cube = {{{0, 0, 0}, {6, 6, 6}}, {{2, 2, 6}, {4, 4, 7}},
                                                         {{6, 1, 1}, {7, 3, 3}}};
  int total_splits = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    Case c = make_case(seed % 2 ? bars : bumpy_cube, {});
    const detail::SolidIndex index(c.mesh);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> coord(-1, 7), axis(0, 5);
    while (c.boxes.size() < 16) {
      Cell lo{coord(rng), coord(rng), coord(rng)}, hi{coord(rng), coord(rng), coord(rng)};
      for (std::size_t k = 0; k < 3; ++k)
        if (lo[k] > hi[k]) std::swap(lo[k], hi[k]);
      if (lo[0] == hi[0] || lo[1] == hi[1] || lo[2] == hi[2]) continue;
      const HeightBox b = hb(lo, hi, static_cast<Axis>(axis(rng)));
      if (!index.box_is_valid(b) || intersect(c.solid, cells_in(b.box)).empty()) continue;
      c.boxes.push_back(b);
    }
    const ResolveResult r1 = resolve_and_check(c);
    ResolveResult r2;
    {
      const ThreadLimit one_thread(1);  // same answer whatever the thread count
      r2 = resolve_overlaps(c.mesh, c.boxes, {});
    }
    ASSERT_EQ(r1.ordered.size(), r2.ordered.size());
    for (std::size_t i = 0; i < r1.ordered.size(); ++i) {
      EXPECT_EQ(r1.ordered[i].box.min, r2.ordered[i].box.min);
      EXPECT_EQ(r1.ordered[i].box.max, r2.ordered[i].box.max);
      EXPECT_EQ(r1.ordered[i].axis, r2.ordered[i].axis);
    }
    total_splits += r1.num_splits;
  }
  EXPECT_GT(total_splits, 0);  // the instances really have cycles
}

}  // namespace
}  // namespace subfab
