// SPDX-License-Identifier: GPL-3.0-or-later
// mill_within_tolerance() (issue 17, point 2): the grooved box as one block
// along +z, whose milled shape fills the groove (1 deep).
#include "subfab/decompose/mill_within_tolerance.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "decompose/block_pairs_detail.h"
#include "subfab/core/error.h"
#include "subfab/validate/measure_fill_deviation.h"
#include "subfab/validate/milled_shape.h"
#include "subfab/validate/validate_decomposition.h"
#include "support/block_test_shapes.h"
#include "support/groove_shapes.h"
#include "validate/validate_booleans.h"

namespace subfab {
namespace {

using test::grooved_box_cells;
using test::voxel_mesh;

std::vector<Block> whole_box(const Mesh& box) { return {Block{box, Axis::PosZ, 0}}; }

TEST(MillWithinTolerance, TheGroovesFillIsMeasuredAgainstTheTolerance) {
  // Filling the groove moves the surface by exactly 1 (groove_shapes.h):
  // within T = 1.5 the bound (measure + 5% of T) lies in [1, 1.5]; at
  // T = 0.9 the block fails.
  const Mesh box = voxel_mesh(grooved_box_cells());
  MillToleranceOptions o;
  o.tolerance = 1.5;
  const MillToleranceResult wide = mill_within_tolerance(box, whole_box(box), o);
  ASSERT_EQ(wide.blocks.size(), 1u);
  EXPECT_EQ(wide.filled[0], 1);
  EXPECT_TRUE(wide.failures[0].empty()) << wide.failures[0];
  EXPECT_GE(wide.deviation[0], 1.0 - 1e-9);
  EXPECT_LE(wide.deviation[0], 1.0 + 2 * o.error_fraction * o.tolerance);
  // Two such boxes side by side, each one block: both bounded over their parts, not measured.
  Mesh pair = box;
  for (const Vec3& v : box.vertices) pair.vertices.push_back(v + Vec3(100, 0, 0));
  for (Triangle t : box.faces) {
    for (int& v : t) v += static_cast<int>(box.vertices.size());
    pair.faces.push_back(t);
  }
  Mesh right = box;
  for (Vec3& v : right.vertices) v += Vec3(100, 0, 0);
  const MillToleranceResult two =
      mill_within_tolerance(pair, {Block{box, Axis::PosZ, 0}, Block{right, Axis::PosZ, 1}}, o);
  EXPECT_EQ(two.num_failed(), 0u);
  EXPECT_EQ(two.num_bounded, 2u);
  for (double d : two.deviation) {
    EXPECT_GE(d, 1.0 - 1e-9);
    EXPECT_LE(d, 1.0 + 2 * o.error_fraction * o.tolerance);
  }
  EXPECT_EQ(wide.max_deviation, wide.deviation[0]);
  EXPECT_EQ(wide.num_bounded, 0u);  // a lone block is measured in regions, on every core (not bounded first)
  EXPECT_TRUE(is_height_field(wide.blocks[0].mesh, axis_direction(Axis::PosZ)));
  o.tolerance = 0.9;
  const MillToleranceResult narrow = mill_within_tolerance(box, whole_box(box), o);
  EXPECT_EQ(narrow.num_failed(), 1u);
  EXPECT_EQ(narrow.num_bounded, 0u);
  EXPECT_EQ(narrow.max_deviation, 0.0);
}

TEST(MillWithinTolerance, AKnownDeviationIsTakenInsteadOfMeasured) {
  // replace_failed_blocks() passes the deviations of the blocks nothing
  // near changed: they are taken as given (here one the measure could never
  // give, to see that it was not measured), the milled shape still made.
  const Mesh box = voxel_mesh(grooved_box_cells());
  MillToleranceOptions o;
  o.tolerance = 1.5;
  const std::vector<char> measure{0};
  const std::vector<double> known{0.25};
  o.measure = &measure;
  o.known_deviation = &known;
  const MillToleranceResult r = mill_within_tolerance(box, whole_box(box), o);
  EXPECT_EQ(r.filled[0], 1);
  EXPECT_TRUE(r.failures[0].empty());
  EXPECT_EQ(r.deviation[0], 0.25);
  EXPECT_EQ(r.max_deviation, 0.25);
  const std::vector<char> measure_all{1};
  o.measure = &measure_all;
  EXPECT_GE(mill_within_tolerance(box, whole_box(box), o).deviation[0], 1.0 - 1e-9);
  const std::vector<double> none;
  o.known_deviation = &none;
  EXPECT_THROW(mill_within_tolerance(box, whole_box(box), o), InvalidArgumentError);
  o.known_deviation = nullptr;
  EXPECT_THROW(mill_within_tolerance(box, whole_box(box), o), InvalidArgumentError);
}

TEST(MillWithinTolerance, ASampledPointBeyondTheToleranceFailsTheBlockBeforeItsMeasure) {
  // The groove's fill moves the surface by 1: at T = 0.9 the sampled lower
  // bound (fill_deviation_lower_bound.h) already fails the block; with
  // stop_at_first_failure the result says nothing was measured.
  const Mesh box = voxel_mesh(grooved_box_cells());
  MillToleranceOptions o;
  o.tolerance = 0.9;
  const MillToleranceResult r = mill_within_tolerance(box, whole_box(box), o);
  ASSERT_EQ(r.num_failed(), 1u);
  EXPECT_NE(r.failures[0].find("a sampled point"), std::string::npos) << r.failures[0];
  EXPECT_FALSE(r.stopped);
  o.stop_at_first_failure = true;
  EXPECT_TRUE(mill_within_tolerance(box, whole_box(box), o).stopped);
  o.tolerance = 1.5;  // within it: measured, nothing stopped
  const MillToleranceResult wide = mill_within_tolerance(box, whole_box(box), o);
  EXPECT_FALSE(wide.stopped);
  EXPECT_EQ(wide.num_failed(), 0u);
}

// With locate_failures, a block the sampled bound fails says where: every
// sampled point farther than T lies in the groove's fill (the outer ring,
// z in [4, 6]), where decompose() lowers the allowances (session 35);
// without it, or for a candidate stopped at its first failure, none.
TEST(MillWithinTolerance, AFailingBlockLocatesItsFarPointsInItsFill) {
  const Mesh box = voxel_mesh(grooved_box_cells());
  MillToleranceOptions o;
  o.tolerance = 0.9;
  EXPECT_TRUE(mill_within_tolerance(box, whole_box(box), o).far_points.at(0).empty());
  o.locate_failures = true;
  const MillToleranceResult r = mill_within_tolerance(box, whole_box(box), o);
  ASSERT_EQ(r.num_failed(), 1u);
  ASSERT_FALSE(r.far_points.at(0).empty());
  for (const Vec3& p : r.far_points[0]) {
    EXPECT_TRUE(p.x() <= 1 || p.x() >= 9 || p.y() <= 1 || p.y() >= 9) << p.transpose();
    EXPECT_GE(p.z(), 4.0);
    EXPECT_LE(p.z(), 6.0);
  }
  o.stop_at_first_failure = true;
  EXPECT_TRUE(mill_within_tolerance(box, whole_box(box), o).far_points.at(0).empty());
  o.stop_at_first_failure = false;
  o.tolerance = 1.5;  // passes: nothing to locate
  EXPECT_TRUE(mill_within_tolerance(box, whole_box(box), o).far_points.at(0).empty());
}

// Regression (session 32, max planck at 3.3e-3): the carved blocks do not
// overlap, so a pair is checked for a collision only where a fill reaches the
// other block. The grooved box with its top corner [5, 10]^2 x [7, 10] carved
// off as a second block B, whose box meets the first's, but not its fill (the
// groove's columns, z <= 6). B has a zero-area face (a vertex in the middle of
// a top edge, as rounding leaves them), on which exact booleans cannot run: the
// pair used to be taken as colliding ("its milled shape overlaps block 2")
// and the grooved block failed, costing a round and a block.
TEST(MillWithinTolerance, ABlockTheFillCannotReachIsNoCollisionEvenWithAZeroAreaFace) {
  std::set<test::Cell> notch, rest;
  for (const test::Cell& c : grooved_box_cells())
    (c[0] >= 5 && c[1] >= 5 && c[2] >= 7 ? notch : rest).insert(c);
  const Mesh solid = voxel_mesh(grooved_box_cells());
  const Mesh a = voxel_mesh(rest);
  // B: the notch as a box whose top edge (5,10,10)-(10,10,10) gets a midpoint
  // and a zero-area face on that edge (test::with_zero_area_face()).
  Mesh b = test::box_solid(Vec3(5, 5, 7), Vec3(10, 10, 10));
  const auto at = [&](int v) { return b.vertices[static_cast<std::size_t>(v)]; };
  std::size_t face = b.faces.size();
  int corner = -1;
  for (std::size_t f = 0; f < b.faces.size() && corner < 0; ++f)
    for (int k = 0; k < 3 && corner < 0; ++k) {
      const Vec3 p = at(b.faces[f][static_cast<std::size_t>(k)]), q = at(b.faces[f][static_cast<std::size_t>((k + 1) % 3)]);
      if (p.z() == 10 && q.z() == 10 && p.y() == 10 && q.y() == 10) face = f, corner = k;
    }
  ASSERT_GE(corner, 0);
  b = test::with_zero_area_face(b, face, corner);
  ASSERT_TRUE(check_closed_solid(b).ok());
  EXPECT_THROW(detail::exact_blocks_overlap(a, b), std::exception);  // no exact boolean on B
  MillToleranceOptions o;
  o.tolerance = 1.5;
  const MillToleranceResult r = mill_within_tolerance(solid, {Block{a, Axis::PosZ, 0}, Block{b, Axis::PosZ, 1}}, o);
  ASSERT_EQ(r.blocks.size(), 2u);
  EXPECT_EQ(r.filled[0], 1);
  EXPECT_EQ(r.filled[1], 0);
  EXPECT_TRUE(r.failures[0].empty()) << r.failures[0];
  EXPECT_TRUE(r.failures[1].empty()) << r.failures[1];
  EXPECT_EQ(r.collided, (std::vector<char>{0, 0}));
  EXPECT_GE(r.deviation[0], 1.0 - 1e-9);  // the groove filled: 1 deep
}

// The mill stage proves a pair of milled shapes apart without a boolean when
// each one's interior misses the other's fill boxes (fill_misses_solid()):
// known answers on the L prism ([0,2]^2 minus [1,2]^2 in xy, z in [0,1]).
TEST(MillWithinTolerance, AFillBoxMissesASolidOnlyWhenNoFaceCrossesItAndItLiesOutside) {
  const Mesh l = test::l_solid();
  const std::unique_ptr<detail::SolidIndex> index = detail::inside_test_index(l);
  ASSERT_NE(index, nullptr);
  const BoundingBox box = bounding_box(l);
  const auto misses = [&](const Vec3& lo, const Vec3& hi) {
    BoundingBox b;
    b.extend(lo);
    b.extend(hi);
    return detail::fill_misses_solid({b}, *index, box);
  };
  EXPECT_TRUE(misses(Vec3(1, 1, 0), Vec3(2, 2, 1)));           // the notch: faces only on its sides
  EXPECT_TRUE(misses(Vec3(1.2, 1.2, 0.2), Vec3(1.8, 1.8, 0.8)));  // inside the notch
  EXPECT_TRUE(misses(Vec3(1, 1, -5), Vec3(3, 3, 5)));          // beyond the bounding box: clipped to the notch
  EXPECT_TRUE(misses(Vec3(5, 5, 5), Vec3(6, 6, 6)));           // far away
  EXPECT_TRUE(misses(Vec3(2, 0, 0), Vec3(3, 1, 1)));           // touching the side x = 2 only
  EXPECT_FALSE(misses(Vec3(0.2, 0.2, 0.2), Vec3(0.4, 0.4, 0.4)));  // inside the solid, no face crossing it
  EXPECT_FALSE(misses(Vec3(0.5, 0.5, 0.5), Vec3(1.5, 1.5, 1.5)));  // across the notch's corner
  EXPECT_FALSE(misses(Vec3(0.9, 1, 0), Vec3(2, 2, 1)));        // a hair into the arm x < 1
  // every box of the list must miss
  BoundingBox notch, inside;
  notch.extend(Vec3(1, 1, 0));
  notch.extend(Vec3(2, 2, 1));
  inside.extend(Vec3(0.2, 0.2, 0.2));
  inside.extend(Vec3(0.4, 0.4, 0.4));
  EXPECT_FALSE(detail::fill_misses_solid({notch, inside}, *index, box));
  // A block the exact booleans refuse (a zero-area face, or crossing itself)
  // gets no index: its pairs are checked exactly, and fail.
  const Mesh cube = test::box_solid(Vec3(0, 0, 0), Vec3(1, 1, 1));
  EXPECT_EQ(detail::inside_test_index(test::with_zero_area_face(cube, 0, 0)), nullptr);
  Mesh crossing = cube;
  const Mesh other = test::box_solid(Vec3(0.5, 0.5, 0.5), Vec3(1.5, 1.5, 1.5));
  for (Triangle t : other.faces) {
    for (int& v : t) v += static_cast<int>(cube.vertices.size());
    crossing.faces.push_back(t);
  }
  crossing.vertices.insert(crossing.vertices.end(), other.vertices.begin(), other.vertices.end());
  EXPECT_EQ(detail::inside_test_index(crossing), nullptr);
}

// The exact overlap clipped near a box known to hold it is the same volume:
// the L prism and a box over its arm x < 1 (overlap [0.5, 1] x [1.5, 2] x
// [0, 1], volume 0.25), clipped in x well inside their common box.
TEST(MillWithinTolerance, TheOverlapClippedNearItsFillIsTheSameVolume) {
  const Mesh l = test::l_solid();
  const Mesh b = test::box_solid(Vec3(0.5, 1.5, -1), Vec3(1.5, 2.5, 2));
  BoundingBox within;
  within.extend(Vec3(0.4, 1.4, -0.1));
  within.extend(Vec3(1.1, 2.1, 1.1));
  EXPECT_NEAR(detail::exact_blocks_overlap(l, b), 0.25, 1e-12);
  EXPECT_EQ(detail::exact_blocks_overlap(l, b, within), detail::exact_blocks_overlap(l, b));
  EXPECT_EQ(detail::exact_blocks_overlap(b, l, within), detail::exact_blocks_overlap(l, b));
  BoundingBox apart;  // no volume of the common box in it
  apart.extend(Vec3(3, 3, 3));
  apart.extend(Vec3(4, 4, 4));
  EXPECT_EQ(detail::exact_blocks_overlap(l, b, apart), 0.0);
}

// A fill that does reach the other block is still a collision: a mushroom
// (stem [4,6]^2 x [0,5], cap [2,8]^2 x [5,7]) milled along +z fills under
// its cap down to z = 0, where a second block [7,8] x [4,6] x [0,5] stands.
TEST(MillWithinTolerance, AFillReachingAnotherBlockIsACollision) {
  std::set<test::Cell> stem = test::cells_of_box({4, 4, 0}, {6, 6, 5});
  std::set<test::Cell> cap = test::cells_of_box({2, 2, 5}, {8, 8, 7});
  std::set<test::Cell> post = test::cells_of_box({7, 4, 0}, {8, 6, 5});
  std::set<test::Cell> mushroom = stem, all;
  mushroom.insert(cap.begin(), cap.end());
  all = mushroom;
  all.insert(post.begin(), post.end());
  const Mesh solid = test::voxel_mesh(all);
  const Mesh a = test::voxel_mesh(mushroom);
  const Mesh b = test::voxel_mesh(post);
  // The fill's finer cover: one column per face of the cap's underside (z =
  // 5, facing away from +z), each down to the base z = 0.
  const MilledShape milled = milled_shape(a, Vec3(0, 0, 1));
  const std::optional<std::vector<BoundingBox>> columns = fill_face_columns(a, milled.mesh, Axis::PosZ);
  ASSERT_TRUE(columns.has_value());
  ASSERT_FALSE(columns->empty());
  BoundingBox covered;
  for (const BoundingBox& c : *columns) {
    EXPECT_EQ(c.min.z(), 0.0);
    EXPECT_EQ(c.max.z(), 5.0);
    covered.extend(c.min);
    covered.extend(c.max);
  }
  EXPECT_EQ(covered.min, Vec3(2, 2, 0));
  EXPECT_EQ(covered.max, Vec3(8, 8, 5));
  EXPECT_LE(tile_columns(*columns, milled.mesh, Axis::PosZ).size(), columns->size());
  MillToleranceOptions o;
  o.tolerance = 50;  // the fill's deviation does not matter here
  const MillToleranceResult r = mill_within_tolerance(solid, {Block{a, Axis::PosZ, 0}, Block{b, Axis::PosZ, 1}}, o);
  ASSERT_EQ(r.blocks.size(), 2u);
  EXPECT_EQ(r.filled[0], 1);
  EXPECT_EQ(r.filled[1], 0);
  EXPECT_EQ(r.failures[0], "its milled shape overlaps block 2");
  EXPECT_TRUE(r.failures[1].empty()) << r.failures[1];
  // both of the pair are marked (the rounds then grow the boxes next to each
  // other afresh, decompose.cpp); the exact post passes all the same
  EXPECT_EQ(r.collided, (std::vector<char>{1, 1}));
  EXPECT_NEAR(detail::exact_blocks_overlap(r.blocks[0].mesh, b), 10.0, 1e-9);  // [7,8] x [4,6] x [0,5]
}

}  // namespace
}  // namespace subfab

namespace subfab {
namespace {

// A block milled before on the same solid (the rounds within a tolerance
// carve many again unchanged) is taken from the cache: the same milled shape,
// fill and measure as without it; a call on another solid empties the cache.
TEST(MillWithinTolerance, ABlockMilledBeforeOnTheSameSolidIsReusedWithTheSameResult) {
  const Mesh box = voxel_mesh(grooved_box_cells());
  MillToleranceOptions o;
  o.tolerance = 1.5;
  const MillToleranceResult plain = mill_within_tolerance(box, whole_box(box), o);
  ASSERT_EQ(plain.filled.at(0), 1);
  MillCache cache;
  o.cache = &cache;
  const MillToleranceResult first = mill_within_tolerance(box, whole_box(box), o);
  EXPECT_EQ(cache.hits(), 0u);
  EXPECT_EQ(cache.size(), 1u);
  const MillToleranceResult again = mill_within_tolerance(box, whole_box(box), o);
  EXPECT_EQ(cache.hits(), 1u);
  EXPECT_EQ(cache.size(), 1u);
  for (const MillToleranceResult* r : {&first, &again}) {
    EXPECT_EQ(r->filled, plain.filled);
    EXPECT_EQ(r->failures, plain.failures);
    EXPECT_EQ(r->deviation, plain.deviation);
    EXPECT_EQ(r->blocks.at(0).mesh.vertices, plain.blocks.at(0).mesh.vertices);
    EXPECT_EQ(r->blocks.at(0).mesh.faces, plain.blocks.at(0).mesh.faces);
  }
  // the block on its own as the solid: another solid, nothing reused
  const Mesh moved = [&] {
    Mesh m = box;
    for (Vec3& v : m.vertices) v += Vec3(0.5, 0, 0);
    return m;
  }();
  const MillToleranceResult other = mill_within_tolerance(moved, whole_box(moved), o);
  EXPECT_EQ(cache.hits(), 1u);
  EXPECT_EQ(cache.size(), 1u);
  EXPECT_EQ(other.filled.at(0), 1);
}

}  // namespace
}  // namespace subfab
