// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/carve_blocks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "support/block_test_shapes.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/finalize_blocks.h"
#include "subfab/validate/validate_decomposition.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

using test::box_solid;
using test::l_solid;
using test::make_height_box;

double total_volume(const CarveResult& r) {
  double v = 0;
  for (const Block& b : r.blocks) v += signed_volume(b.mesh);
  return v;
}

//! Every undirected edge is used exactly twice, once in each direction.
bool is_closed_oriented(const Mesh& m) {
  std::map<std::pair<int, int>, int> count;
  for (const Triangle& t : m.faces)
    for (int k = 0; k < 3; ++k) ++count[{t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]}];
  for (const auto& [e, c] : count) {
    if (c != 1) return false;
    auto it = count.find({e.second, e.first});
    if (it == count.end() || it->second != 1) return false;
  }
  return !m.faces.empty();
}

TEST(CarveBlocks, LShapeFromTwoOverlappingBoxes) {
  const Mesh solid = l_solid();
  const std::vector<HeightBox> boxes = {make_height_box({0, 0, 0}, {2, 1, 1}, Axis::PosZ),
                                        make_height_box({0, 0, 0}, {1, 2, 1}, Axis::PosY)};
  const CarveResult r = carve_blocks(solid, boxes);
  ASSERT_EQ(r.blocks.size(), 2u);
  EXPECT_NEAR(signed_volume(r.blocks[0].mesh), 2.0, 1e-12);
  EXPECT_NEAR(signed_volume(r.blocks[1].mesh), 1.0, 1e-12);  // the first box took the overlap
  EXPECT_EQ(r.blocks[0].axis, Axis::PosZ);
  EXPECT_EQ(r.blocks[1].axis, Axis::PosY);
  EXPECT_EQ(r.blocks[1].source_box, 1);
  for (const Block& b : r.blocks) EXPECT_TRUE(is_closed_oriented(b.mesh));
  const BoundingBox bb = bounding_box(r.blocks[1].mesh);
  EXPECT_EQ(bb.min.y(), 1.0);  // exact cut on the first box's plane
  EXPECT_EQ(r.num_flipped_faces + r.num_degenerate_faces, 0u);
}

TEST(CarveBlocks, OrderDecidesWhoTakesTheOverlap) {
  const Mesh solid = l_solid();
  const std::vector<HeightBox> boxes = {make_height_box({0, 0, 0}, {1, 2, 1}, Axis::PosY),
                                        make_height_box({0, 0, 0}, {2, 1, 1}, Axis::PosZ)};
  const CarveResult r = carve_blocks(solid, boxes);
  ASSERT_EQ(r.blocks.size(), 2u);
  EXPECT_NEAR(signed_volume(r.blocks[0].mesh), 2.0, 1e-12);
  EXPECT_NEAR(signed_volume(r.blocks[1].mesh), 1.0, 1e-12);
  EXPECT_EQ(bounding_box(r.blocks[1].mesh).min.x(), 1.0);
}

TEST(CarveBlocks, ClipsSlantedSurfaceExactly) {
  // A wedge: unit square base, top rising from z = 1 at x = 0 to z = 2 at x = 1.
  Mesh wedge = box_solid({0, 0, 0}, {1, 1, 1});
  for (Vec3& v : wedge.vertices)
    if (v.z() == 1.0 && v.x() == 1.0) v.z() = 2.0;
  // Two boxes along +z: the halves x < 0.5 and x > 0.5 (overlapping a bit).
  const std::vector<HeightBox> boxes = {make_height_box({-1, -1, -1}, {0.5, 2, 3}, Axis::PosZ),
                                        make_height_box({0.25, -1, -1}, {2, 2, 3}, Axis::PosZ)};
  const CarveResult r = carve_blocks(wedge, boxes);
  ASSERT_EQ(r.blocks.size(), 2u);
  // Volume of the wedge: 1.5; left half: 0.5 * 1.25 = 0.625.
  EXPECT_NEAR(signed_volume(r.blocks[0].mesh), 0.625, 1e-12);
  EXPECT_NEAR(total_volume(r), 1.5, 1e-12);
  for (const Block& b : r.blocks) EXPECT_TRUE(is_closed_oriented(b.mesh));
}

TEST(CarveBlocks, DropsPiecesThatTouchNoSurface) {
  const Mesh solid = box_solid({0, 0, 0}, {3, 3, 3});
  const std::vector<HeightBox> boxes = {
      make_height_box({0, 0, 0}, {3, 3, 1}, Axis::NegZ), make_height_box({0, 0, 2}, {3, 3, 3}, Axis::PosZ),
      make_height_box({1, 1, 1}, {2, 2, 2}, Axis::PosX),  // strictly inside: an interior piece
      make_height_box({0, 0, 0}, {3, 3, 3}, Axis::PosX)};  // the middle slab: touches the sides
  const CarveResult r = carve_blocks(solid, boxes);
  ASSERT_EQ(r.blocks.size(), 3u);
  EXPECT_EQ(r.num_dropped_pieces, 1u);
  EXPECT_EQ(r.blocks[2].source_box, 3);
  // The slab minus the interior cube.
  EXPECT_NEAR(signed_volume(r.blocks[2].mesh), 9.0 - 1.0, 1e-12);
}

TEST(CarveBlocks, KeepsBoxFlushWithTheSurface) {
  // The box coincides with the solid: every face of the piece lies on a box plane.
  const Mesh solid = box_solid({0, 0, 0}, {1, 1, 1});
  const CarveResult r = carve_blocks(solid, {make_height_box({0, 0, 0}, {1, 1, 1}, Axis::PosZ)});
  ASSERT_EQ(r.blocks.size(), 1u);
  EXPECT_NEAR(signed_volume(r.blocks[0].mesh), 1.0, 1e-12);
}

TEST(CarveBlocks, NonManifoldRegionIsCutIntoPieces) {
  // Region of the last box = two unit cubes touching along an edge.
  const Mesh solid = box_solid({0, 0, 0}, {2, 2, 1});
  const std::vector<HeightBox> boxes = {make_height_box({0, 0, 0}, {1, 1, 1}, Axis::PosZ),
                                        make_height_box({1, 1, 0}, {2, 2, 1}, Axis::PosZ),
                                        make_height_box({0, 0, 0}, {2, 2, 1}, Axis::PosZ)};
  const CarveResult r = carve_blocks(solid, boxes);
  ASSERT_EQ(r.blocks.size(), 4u);
  EXPECT_NEAR(total_volume(r), 4.0, 1e-12);
  for (const Block& b : r.blocks) {
    EXPECT_TRUE(is_closed_oriented(b.mesh));
    EXPECT_NEAR(signed_volume(b.mesh), 1.0, 1e-12);
  }
}

//! A 2 x 2 x 1 slab with a V notch cut into its y = 0 side; the apex edge of
//! the notch is the vertical edge x = 1, y = 1 (volume 4 - 0.5 = 3.5).
Mesh notched_slab() {
  return test::extrude_polygon({{0, 0}, {0.5, 0}, {1, 1}, {1.5, 0}, {2, 0}, {2, 2}, {0, 2}},
                               {{6, 0, 1}, {6, 1, 2}, {6, 2, 5}, {5, 2, 3}, {5, 3, 4}}, 0.0, 1.0);
}

TEST(CarveBlocks, SolidTouchingBoxPlaneAlongAnEdgeGivesSeparatePieces) {
  // The box's plane y = 1 holds the notch's apex edge: solid ∩ box is two
  // prisms touching along that edge (not a 2-manifold), carved as 2 blocks.
  const Mesh solid = notched_slab();
  ASSERT_NEAR(signed_volume(solid), 3.5, 1e-12);
  const CarveResult r = carve_blocks(solid, {make_height_box({0, 0, 0}, {2, 1, 1}, Axis::PosZ)});
  ASSERT_EQ(r.blocks.size(), 2u);
  for (const Block& b : r.blocks) {
    EXPECT_TRUE(is_closed_oriented(b.mesh));
    EXPECT_NEAR(signed_volume(b.mesh), 0.75, 1e-12);
    EXPECT_EQ(b.source_box, 0);
  }
  // One piece on each side of the edge.
  EXPECT_EQ(bounding_box(r.blocks[0].mesh).max.x() + bounding_box(r.blocks[1].mesh).max.x(), 3.0);
}

TEST(CarveBlocks, SolidEdgeOnBoxPlaneInAnyDirection) {
  // The same notch turned about y by 30 degrees: the apex edge still lies in
  // the plane y = 1, now slanted within it.
  Mesh solid = notched_slab();
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  for (Vec3& v : solid.vertices) v = Vec3(c * v.x() + s * v.z(), v.y(), -s * v.x() + c * v.z());
  const CarveResult r = carve_blocks(solid, {make_height_box({-5, -5, -5}, {5, 1, 5}, Axis::PosZ),
                                             make_height_box({-5, 1, -5}, {5, 5, 5}, Axis::NegY)});
  ASSERT_EQ(r.blocks.size(), 3u);
  for (const Block& b : r.blocks) EXPECT_TRUE(is_closed_oriented(b.mesh));
  EXPECT_NEAR(signed_volume(r.blocks[0].mesh), 0.75, 1e-9);
  EXPECT_NEAR(signed_volume(r.blocks[1].mesh), 0.75, 1e-9);
  EXPECT_NEAR(signed_volume(r.blocks[2].mesh), 2.0, 1e-9);
  EXPECT_EQ(r.blocks[2].source_box, 1);
}

TEST(CarveBlocks, EarlierBoxLeavesPiecesTouchingAlongAnEdge) {
  // The earlier box takes the notched slab's upper half; the later box's
  // region then holds the two prisms below y = 1, which touch along the apex edge.
  const Mesh solid = notched_slab();
  const CarveResult r = carve_blocks(solid, {make_height_box({0, 1, 0}, {2, 2, 1}, Axis::PosY),
                                             make_height_box({0, 0, 0}, {2, 2, 1}, Axis::PosZ)});
  ASSERT_EQ(r.blocks.size(), 3u);
  EXPECT_NEAR(signed_volume(r.blocks[0].mesh), 2.0, 1e-12);
  for (std::size_t i = 1; i < 3; ++i) {
    EXPECT_TRUE(is_closed_oriented(r.blocks[i].mesh));
    EXPECT_NEAR(signed_volume(r.blocks[i].mesh), 0.75, 1e-12);
  }
  EXPECT_NEAR(total_volume(r), 3.5, 1e-12);
}

//! A 4 x 4 column from z = -1 to 1 whose top is a square dimple: an inverted
//! pyramid with its apex at (2, 2, 0) (volume 32 - 16 / 3).
Mesh dimpled_column() {
  Mesh m;
  m.vertices = {{0, 0, -1}, {4, 0, -1}, {4, 4, -1}, {0, 4, -1}, {0, 0, 1}, {4, 0, 1}, {4, 4, 1}, {0, 4, 1}, {2, 2, 0}};
  m.faces = {{0, 2, 1}, {0, 3, 2}, {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5}, {2, 3, 7},
             {2, 7, 6}, {3, 0, 4}, {3, 4, 7}, {4, 5, 8}, {5, 6, 8}, {6, 7, 8}, {7, 4, 8}};
  return m;
}

TEST(CarveBlocks, SurfaceTouchingTheBoxFromInsideIsCutThroughTheContact) {
  // Regression (elephant, box 201 of 213 at default settings): the box's
  // bottom plane z = 0 holds the dimple's apex, a vertex of the top surface.
  // solid ∩ box is then one connected solid whose thickness drops to zero at
  // the apex (not a 2-manifold there); it used to come out as ONE block with
  // two vertices at the apex, touching itself, which finalize_blocks then
  // refused ("it self-intersects"). The region is now cut by a plane through
  // the apex, into two valid blocks.
  const Mesh solid = dimpled_column();
  ASSERT_NEAR(signed_volume(solid), 32.0 - 16.0 / 3.0, 1e-12);
  const CarveResult r = carve_blocks(solid, {make_height_box({0.5, 0.5, 0}, {3.5, 3.5, 2}, Axis::PosZ)});
  ASSERT_EQ(r.blocks.size(), 2u);
  EXPECT_EQ(r.num_pinched_regions, 1u);
  EXPECT_EQ(r.num_unresolved_pinches, 0u);
  EXPECT_NEAR(total_volume(r), 4.5, 1e-12);
  for (const Block& b : r.blocks) {
    EXPECT_TRUE(is_closed_oriented(b.mesh));
    EXPECT_NEAR(signed_volume(b.mesh), 2.25, 1e-12);
    EXPECT_EQ(block_defect(b.mesh, Vec3::UnitZ(), 6.0), "");
  }
  // One block on each side of the plane x = 2 through the apex.
  EXPECT_EQ(bounding_box(r.blocks[0].mesh).max.x() + bounding_box(r.blocks[1].mesh).max.x(), 5.5);
}

//! A solid over x in [0, 2], z in [-1, 2], 0 <= y: a thick part (y <= 1.9)
//! for z <= 0, then for z >= 0 a top y = 1 + |x - g(z)| / 2 with
//! g(z) = 0.75 + z / 2: a V-shaped valley whose floor, at height y = 1,
//! runs SLANTED in x-z from (0.75, 1, 0) to (1.75, 1, 2).
Mesh slanted_valley() {
  Mesh m;
  m.vertices = {{0, 0, -1},     {2, 0, -1},   {2, 0, 2},     {0, 0, 2},     {0, 1.9, -1},
                {2, 1.9, -1},   {2, 1.9, 0},  {0, 1.9, 0},   {0, 1.375, 0}, {0.75, 1, 0},
                {2, 1.625, 0},  {0, 1.875, 2}, {1.75, 1, 2}, {2, 1.125, 2}};
  m.faces = {{0, 1, 2},   {0, 2, 3},   {0, 4, 5},   {0, 5, 1},   {4, 7, 6},   {4, 6, 5},  {9, 10, 6},
             {9, 6, 7},   {9, 7, 8},   {3, 12, 11}, {3, 13, 12}, {3, 2, 13},  {0, 3, 11}, {0, 11, 8},
             {0, 8, 7},   {0, 7, 4},   {1, 5, 6},   {1, 6, 10},  {1, 10, 13}, {1, 13, 2}, {8, 11, 12},
             {8, 12, 9},  {9, 12, 13}, {9, 13, 10}};
  return m;
}

TEST(CarveBlocks, SlantedContactIsSeparatedByMovingTheBoxFaceOffIt) {
  // Regression (couplingdown, boxes 62 and 69 at default settings): the top
  // face y = 1 of an earlier box holds the floor of a valley of the surface
  // along a segment slanted in x-z. The later box's region (y >= 1, z <= 0.9)
  // meets the solid in two wedges that touch along that segment and are
  // joined to the thick part below z = 0: ONE piece touching itself. The
  // contact ends at z = 0.9 at x = 1.2 + 1e-17 (not a double) and lies in
  // the earlier box's face, so no axis-aligned plane can cut it apart; the
  // block touched itself and finalize_blocks() refused it ("it
  // self-intersects"). Now the earlier box's top face is moved off the
  // contact (the box grows by 1e-6 of the diagonal and stays exactly
  // valid), which leaves the wedges apart.
  const Mesh solid = slanted_valley();
  const SolidReport report = check_closed_solid(solid);
  ASSERT_EQ(report.num_boundary_edges + report.num_non_manifold_edges, 0u);
  ASSERT_GT(report.volume, 0.0);
  const std::vector<HeightBox> boxes = {make_height_box({0, 0, -1}, {2, 1, 2}, Axis::PosY),
                                        make_height_box({0, 0, -1}, {2, 2, 0.9}, Axis::PosY)};
  const CarveResult r = carve_blocks(solid, boxes);
  EXPECT_EQ(r.num_unresolved_pinches, 0u);
  EXPECT_EQ(r.num_moved_faces, 1u);
  ASSERT_EQ(r.blocks.size(), 2u);
  // solid ∩ (B_0 ∪ B_1): all of it for z <= 0.9 (the section area for z >= 0
  // is quadratic in z: Simpson is exact), the part below y = 1 + delta beyond
  // (up to 2.2 delta^2).
  auto area = [](double z) {
    const double g = 0.75 + 0.5 * z;
    return 2.0 + (g * g + (2.0 - g) * (2.0 - g)) / 4.0;
  };
  const double delta = 1e-6 * bounding_box(solid).diagonal();
  const double expected = 3.8 + 0.9 / 6.0 * (area(0.0) + 4.0 * area(0.45) + area(0.9)) + 2.2 * (1.0 + delta);
  EXPECT_NEAR(total_volume(r), expected, 1e-9);
  for (const Block& b : r.blocks) {
    EXPECT_TRUE(is_closed_oriented(b.mesh));
    EXPECT_EQ(block_defect(b.mesh, Vec3::UnitY(), 4.1), "") << "block from box " << b.source_box;
  }
  // The earlier box took the solid up to y = 1 + delta.
  EXPECT_NEAR(bounding_box(r.blocks[0].mesh).max.y(), 1.0 + delta, 1e-15);
}

TEST(CarveBlocks, ContactMoveThatWouldNotchALaterBoxMovesTheFaceInwardInstead) {
  // Regression (anchor.off, boxes 3 and 79 at default settings): the contact
  // lies in the top face y = 1 of box 0. The outward move (box 0 grows to
  // y = 1 + delta) is valid for box 0 but cuts a notch delta high out of the
  // bottom of the later box 2, which abuts that face from above over part of
  // its length (z in [1, 1.5]): box 2's block would have faces facing -y
  // delta above its base (not a height field). That move is taken back; it
  // used to be the only one tried, so the contact stayed and decompose
  // exited 3 ("it self-intersects"). Now the inward move (box 0 shrinks to
  // y = 1 - delta; boxes 1 and 3 hold what it gives up) is tried next.
  const Mesh solid = slanted_valley();
  const std::vector<HeightBox> boxes = {make_height_box({0, 0, -1}, {2, 1, 1.5}, Axis::PosY),
                                        make_height_box({0, 0, -1}, {2, 2, 0.9}, Axis::PosY),
                                        make_height_box({0, 1, 1}, {0.5, 2, 2}, Axis::PosY),
                                        make_height_box({0, 0, 0.9}, {2, 2, 1.5}, Axis::PosY),
                                        make_height_box({0, 0, 1.5}, {2, 2, 2}, Axis::PosY)};
  const CarveResult r = carve_blocks(solid, boxes);
  EXPECT_EQ(r.num_unresolved_pinches, 0u);
  EXPECT_EQ(r.num_moved_faces, 1u);
  // The boxes cover the solid: the blocks are all of it.
  EXPECT_NEAR(total_volume(r), signed_volume(solid), 1e-9);
  std::map<int, double> top_of_box;
  for (const Block& b : r.blocks) {
    EXPECT_TRUE(is_closed_oriented(b.mesh));
    EXPECT_EQ(block_defect(b.mesh, Vec3::UnitY(), 4.1), "") << "block from box " << b.source_box;
    top_of_box[b.source_box] = std::max(top_of_box[b.source_box], bounding_box(b.mesh).max.y());
  }
  ASSERT_EQ(top_of_box.size(), 5u);
  // Box 0 gave up the slab under the contact.
  const double delta = 1e-6 * bounding_box(solid).diagonal();
  EXPECT_NEAR(top_of_box[0], 1.0 - delta, 1e-15);
}

TEST(CarveBlocks, PieceTouchingItselfIsCutBeforeTheHolesAreSubtracted) {
  // Regression (couplingdown.off with the reverted commit 3d12e37, boxes 24
  // and 123 of its carve order; data/regression/README.md): the solid
  // clipped to box 1 touches itself at 2 points, and CGAL 5.5's
  // corefine_and_compute_difference, which requires meshes that do not
  // self-intersect, segfaulted subtracting box 0 from it (decompose exit
  // 139). The region is now cut through the contact first.
  const Mesh solid = read_mesh(test::data_path("regression/couplingdown_canonical.off"));
  const Box3 hole{Vec3(-0x1.a90e66cb10343p-3, -0x1.22f0e0a84be4p-3, -0x1.9c2cf1d092543p-6),
                  Vec3(0x1.352220bc382a1p-4, 0x1.22f0e0a84be4p-3, -0x1.1b5f01175734ap-6)};
  const Box3 box{Vec3(-0x1.cc53cb592f464p-5, -0x1.21cfbb949624ap-2, -0x1.656eefa1e3eafp-3),
                 Vec3(0x1.e97579ffa05ebp-5, 0x1.21cfbb949624ap-2, 0x1.656eefa1e3eafp-3)};
  const std::vector<HeightBox> boxes = {make_height_box(hole.min, hole.max, Axis::NegZ),
                                        make_height_box(box.min, box.max, Axis::NegX)};
  const CarveResult r = carve_blocks(solid, boxes);
  EXPECT_GT(r.num_pinch_cuts, 0u);
  EXPECT_EQ(r.num_unresolved_pinches, 0u);
  EXPECT_EQ(r.num_split_regions, 0u);
  for (const Block& b : r.blocks) {
    EXPECT_TRUE(is_closed_oriented(b.mesh));
    EXPECT_EQ(block_defect(b.mesh, axis_direction(boxes[static_cast<std::size_t>(b.source_box)].axis), 1.0), "")
        << "block from box " << b.source_box;
  }
  // Inclusion-exclusion: the blocks are the solid in the union of the boxes.
  auto carved_volume = [&](const Box3& b) {
    return total_volume(carve_blocks(solid, {make_height_box(b.min, b.max, Axis::PosZ)}));
  };
  Box3 common = hole;
  common.min = common.min.cwiseMax(box.min);
  common.max = common.max.cwiseMin(box.max);
  const double expected = carved_volume(hole) + carved_volume(box) - carved_volume(common);
  EXPECT_NEAR(total_volume(r), expected, 1e-12);
}

TEST(CarveBlocks, SameResultWhateverTheThreadCount) {
  Mesh wedge = box_solid({0, 0, 0}, {1, 1, 1});
  for (Vec3& v : wedge.vertices)
    if (v.z() == 1.0 && v.y() == 1.0) v.z() = 1.7;
  std::vector<HeightBox> boxes;
  for (int i = 0; i < 6; ++i)
    boxes.push_back(make_height_box({0.15 * i - 0.1, -1, -1}, {0.15 * i + 0.3, 2, 3}, Axis::PosZ));
  CarveResult one, many;
  {
    ThreadLimit limit(1);
    one = carve_blocks(wedge, boxes);
  }
  many = carve_blocks(wedge, boxes);
  // Twice in parallel, after unrelated heap traffic.
  std::vector<std::vector<int>> noise;
  for (int i = 0; i < 1000; ++i) noise.emplace_back(static_cast<std::size_t>(i % 37 + 1), i);
  const CarveResult again = carve_blocks(wedge, boxes);
  ASSERT_EQ(again.blocks.size(), many.blocks.size());
  for (std::size_t i = 0; i < again.blocks.size(); ++i) EXPECT_EQ(again.blocks[i].mesh.faces, many.blocks[i].mesh.faces);
  ASSERT_EQ(one.blocks.size(), many.blocks.size());
  for (std::size_t i = 0; i < one.blocks.size(); ++i) {
    EXPECT_EQ(one.blocks[i].mesh.vertices, many.blocks[i].mesh.vertices);
    EXPECT_EQ(one.blocks[i].mesh.faces, many.blocks[i].mesh.faces);
  }
}

}  // namespace
}  // namespace subfab
