// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/validate/milled_shape.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/validate/validate_decomposition.h"
#include "support/block_test_shapes.h"
#include "support/voxel_solid.h"

namespace subfab {
namespace {

using test::box_solid;
using test::union_of_boxes;

//! A box [0,2)x[0,2)x[0,3) with a shelf [2,5)x[0,2)x[2,3) sticking out over
//! empty space (flush with its top): milled along +z, the 3 x 2 x 2 space
//! under the shelf is filled; the farthest filled point is 2 below the shelf.
Mesh shelf() { return union_of_boxes({{{0, 0, 0}, {2, 2, 3}}, {{2, 0, 2}, {5, 2, 3}}}); }

//! A cap [0,4)^2 x [2,3) on a stem [1,3)^2 x [0,2): the ring under the cap is
//! filled (volume 4 x 4 x 2 - 2 x 2 x 2 = 24); its farthest point from the
//! block is a bottom corner of the cap's outline, sqrt(2) from the stem.
Mesh mushroom() { return union_of_boxes({{{1, 1, 0}, {3, 3, 2}}, {{0, 0, 2}, {4, 4, 3}}}); }

//! A slab [0,4)x[0,2)x[0,1), a tower [2,4)x[0,2)x[1,4) and an arm
//! [0,2)x[0,2)x[3,4) over the slab: a step with a gap of 2 under the arm; the
//! milled wall at x = 0 is the slab's side, then new, then the arm's side.
Mesh stepped_arm() {
  return union_of_boxes({{{0, 0, 0}, {4, 2, 1}}, {{2, 0, 1}, {4, 2, 4}}, {{0, 0, 3}, {2, 2, 4}}});
}

Mesh rotated(Mesh m, const Eigen::Matrix3d& r) {
  for (Vec3& v : m.vertices) v = r * v;
  return m;
}

//! Closed, consistently oriented, and a height field along d: nothing faces
//! away from d off the base. With a frame that is not a signed permutation,
//! rounding leaves needles (faces of zero area along near-vertical block
//! faces) whose normals mean nothing: those are allowed (`rounded`).
void expect_milled_solid(const MilledShape& s, const Vec3& d, bool rounded = false) {
  const SolidReport solid = check_closed_solid(s.mesh);
  EXPECT_TRUE(solid.ok()) << solid.num_boundary_edges << " boundary, " << solid.num_non_manifold_edges
                          << " non-manifold edges";
  EXPECT_EQ(solid.num_degenerate_faces, 0u);
  EXPECT_EQ(s.face_kinds.size(), s.mesh.num_faces());
  HeightFieldOptions o;
  o.normal_tolerance = 0.0;
  if (!rounded) {
    const HeightFieldReport hf = check_height_field(s.mesh, d, o);
    EXPECT_TRUE(hf.ok()) << hf.num_overhang_faces << " faces overhang, worst " << hf.worst_cosine;
    return;
  }
  double base = std::numeric_limits<double>::infinity();
  for (const Vec3& v : s.mesh.vertices) base = std::min(base, v.dot(d));
  for (std::size_t f = 0; f < s.mesh.num_faces(); ++f) {
    if (face_unit_normal(s.mesh, f).dot(d) >= -1e-9) continue;
    bool on_base = true;
    for (int v : s.mesh.faces[f]) on_base = on_base && s.mesh.vertices[static_cast<std::size_t>(v)].dot(d) - base < 1e-12;
    EXPECT_TRUE(on_base || face_area(s.mesh, f) < 1e-12) << "face " << f << " faces away, area " << face_area(s.mesh, f);
  }
}

TEST(MilledShape, AnExactHeightFieldIsItsOwnMilledShape) {
  const Mesh box = box_solid({0, 0, 0}, {2, 3, 1});
  for (const Vec3& d : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0, -1, 0)}) {
    const MilledShape s = milled_shape(box, d);
    EXPECT_TRUE(s.is_block);
    EXPECT_EQ(s.mesh.vertices, box.vertices);
    EXPECT_EQ(s.mesh.faces, box.faces);
  }
  // A step is a height field too (its riser is a vertical face).
  const Mesh step = union_of_boxes({{{0, 0, 0}, {4, 2, 1}}, {{0, 0, 1}, {2, 2, 3}}});
  EXPECT_TRUE(milled_shape(step, Vec3::UnitZ()).is_block);
}

TEST(MilledShape, FillsUnderAShelf) {
  const MilledShape s = milled_shape(shelf(), Vec3::UnitZ());
  EXPECT_FALSE(s.is_block);
  expect_milled_solid(s, Vec3::UnitZ());
  EXPECT_DOUBLE_EQ(signed_volume(s.mesh), 30.0);  // the box [0,5]x[0,2]x[0,3]
  EXPECT_DOUBLE_EQ(s.base, 0.0);
  const BoundingBox bb = bounding_box(s.mesh);
  EXPECT_EQ(bb.min, Vec3(0, 0, 0));
  EXPECT_EQ(bb.max, Vec3(5, 2, 3));
  std::size_t walls = 0, bases = 0;
  for (MilledFaceKind k : s.face_kinds) {
    walls += k == MilledFaceKind::Wall;
    bases += k == MilledFaceKind::Base;
  }
  EXPECT_GT(walls, 0u);
  EXPECT_GT(bases, 0u);
}

TEST(MilledShape, FillsUnderAMushroomCapAndAnArmOverAStep) {
  const MilledShape m = milled_shape(mushroom(), Vec3::UnitZ());
  expect_milled_solid(m, Vec3::UnitZ());
  EXPECT_DOUBLE_EQ(signed_volume(m.mesh), 48.0);
  const MilledShape a = milled_shape(stepped_arm(), Vec3::UnitZ());
  expect_milled_solid(a, Vec3::UnitZ());
  EXPECT_DOUBLE_EQ(signed_volume(a.mesh), 32.0);  // block 24, gap 2 x 2 x 2 under the arm
}

//! `m` with the edge between the vertices at p and q split at its midpoint
//! (both faces on it split in two): still closed and manifold.
Mesh split_edge(Mesh m, const Vec3& p, const Vec3& q) {
  const auto at = [&](const Vec3& x) {
    return static_cast<int>(std::find(m.vertices.begin(), m.vertices.end(), x) - m.vertices.begin());
  };
  const int u = at(p), v = at(q), mid = static_cast<int>(m.vertices.size());
  m.vertices.push_back((p + q) / 2.0);
  std::vector<Triangle> faces;
  for (const Triangle& t : m.faces) {
    int k = 0;
    while (k < 3 && !((t[k] == u && t[(k + 1) % 3] == v) || (t[k] == v && t[(k + 1) % 3] == u))) ++k;
    if (k == 3) {
      faces.push_back(t);
      continue;
    }
    const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
    faces.push_back({a, mid, c});
    faces.push_back({mid, b, c});
  }
  m.faces = std::move(faces);
  return m;
}

TEST(MilledShape, ATopEdgeTouchedInsideByAnotherTopFacesCorner) {
  // A slab [0,4)x[0,2)x[0,1), a tower [0,2)x[0,2)x[1,3) on it and a shelf
  // [-2,0)x[0,2)x[2,3) off the tower over empty space. The riser's foot at
  // x = 2 is split at (2, 0.5, 1): seen from +z the slab top's new corner
  // lies inside the tower top's edge (2,0)-(2,1) (the planar map's edges
  // touch, not only at common ends). Milled: the slab, the tower and the
  // shelf's column down to the base.
  const Mesh plain = union_of_boxes({{{0, 0, 0}, {4, 2, 1}}, {{0, 0, 1}, {2, 2, 3}}, {{-2, 0, 2}, {0, 2, 3}}});
  const Mesh touched = split_edge(plain, Vec3(2, 0, 1), Vec3(2, 1, 1));
  ASSERT_EQ(touched.num_faces(), plain.num_faces() + 2);
  ASSERT_TRUE(check_closed_solid(touched).ok());
  for (const Mesh* m : {&plain, &touched}) {
    const MilledShape s = milled_shape(*m, Vec3::UnitZ());
    EXPECT_FALSE(s.is_block);
    expect_milled_solid(s, Vec3::UnitZ());
    EXPECT_DOUBLE_EQ(signed_volume(s.mesh), 28.0);  // 8 + 8 + the shelf's column 2 x 2 x 3
    const BoundingBox bb = bounding_box(s.mesh);
    EXPECT_EQ(bb.min, Vec3(-2, 0, 0));
    EXPECT_EQ(bb.max, Vec3(4, 2, 3));
  }
}

TEST(MilledShape, AnyAxisDirection) {
  // The shelf turned so that its top faces -x, +y, -z: the same milled volume.
  Eigen::Matrix3d to_neg_x, to_pos_y, to_neg_z;
  to_neg_x << 0, 0, -1, 0, 1, 0, 1, 0, 0;  // z -> -x
  to_pos_y << 1, 0, 0, 0, 0, 1, 0, -1, 0;  // z -> +y
  to_neg_z << 1, 0, 0, 0, -1, 0, 0, 0, -1;  // z -> -z
  for (const Eigen::Matrix3d& r : {to_neg_x, to_pos_y, to_neg_z}) {
    const Vec3 d = r * Vec3::UnitZ();
    const MilledShape s = milled_shape(rotated(shelf(), r), d);
    EXPECT_FALSE(s.is_block);
    expect_milled_solid(s, d);
    EXPECT_DOUBLE_EQ(signed_volume(s.mesh), 30.0);
    EXPECT_DOUBLE_EQ(s.base, 0.0);
  }
}

TEST(MilledShape, ObliqueDirectionAndGivenFrame) {
  // An arbitrary rotation: coordinates are rounded, the topology is not.
  const Eigen::Matrix3d r =
      (Eigen::AngleAxisd(0.3, Vec3::UnitX()) * Eigen::AngleAxisd(-0.7, Vec3::UnitY())).toRotationMatrix();
  const Vec3 d = r * Vec3::UnitZ();
  const Mesh block = rotated(mushroom(), r);
  const MilledShape s = milled_shape(block, d);
  expect_milled_solid(s, d, true);
  EXPECT_NEAR(signed_volume(s.mesh), 48.0, 1e-9);
  MilledShapeOptions o;
  o.frame = r.transpose();  // takes d to +z
  const MilledShape f = milled_shape(block, d, o);
  expect_milled_solid(f, d, true);
  EXPECT_NEAR(signed_volume(f.mesh), 48.0, 1e-9);
  o.frame = Eigen::Matrix3d::Identity();  // does not take d to +z
  EXPECT_THROW(milled_shape(block, d, o), InvalidArgumentError);
  EXPECT_THROW(milled_shape(block, 2.0 * d), InvalidArgumentError);
}

TEST(MilledShape, MillingFrameIsARotationTakingTheDirectionToZ) {
  for (const Vec3& d : {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1),
                        Vec3(0, 0, -1), Vec3(Vec3(1, 2, -2) / 3.0)}) {
    const Eigen::Matrix3d q = milling_frame(d);
    EXPECT_NEAR((q * d - Vec3::UnitZ()).norm(), 0.0, 1e-15) << d.transpose();
    EXPECT_NEAR((q.transpose() * q - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-15);
    EXPECT_NEAR(q.determinant(), 1.0, 1e-15);
  }
}

// ------------------------------------------------------------ measures

MilledShapesReport measure(const Mesh& input, const std::vector<std::pair<const Mesh*, Vec3>>& blocks) {
  std::vector<MilledBlockInput> in;
  for (const auto& [mesh, d] : blocks) in.push_back({mesh, d, std::nullopt});
  return measure_milled_shapes(input, in);
}

TEST(MeasureMilledShapes, ExactBlocksCostNothingAndMeasureZero) {
  const Mesh a = box_solid({0, 0, 0}, {1, 1, 1}), b = box_solid({1, 0, 0}, {2, 1, 1});
  const Mesh input = box_solid({0, 0, 0}, {2, 1, 1});
  const MilledShapesReport r = measure(input, {{&a, Vec3::UnitZ()}, {&b, -Vec3::UnitX()}});
  ASSERT_EQ(r.blocks.size(), 2u);
  EXPECT_EQ(r.num_exact(), 2u);
  EXPECT_EQ(r.max_deviation(), 0.0);
  EXPECT_EQ(r.total_filled_volume(), 0.0);
  EXPECT_EQ(r.num_pairs_checked, 0u);  // exact pairs are check 3's
  EXPECT_TRUE(r.collisions.empty());
}

TEST(MeasureMilledShapes, ShelfFilledVolumeAndDeviationAreKnown) {
  const Mesh block = shelf();
  for (const Eigen::Matrix3d& r : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()),
                                   Eigen::Matrix3d((Eigen::Matrix3d() << 0, 0, -1, 0, 1, 0, 1, 0, 0).finished())}) {
    const Mesh turned = rotated(block, r);
    const MilledShapesReport rep = measure(turned, {{&turned, r * Vec3::UnitZ()}});
    const MilledShapeMeasures& m = rep.blocks.at(0);
    EXPECT_FALSE(m.exact);
    EXPECT_TRUE(m.error.empty()) << m.error;
    EXPECT_DOUBLE_EQ(m.block_volume, 18.0);
    EXPECT_DOUBLE_EQ(m.filled_volume, 12.0);
    // The input is the block: the deviation is the depth under the shelf.
    EXPECT_NEAR(m.deviation, 2.0, rep.hausdorff_error + 1e-12);
    EXPECT_NEAR(m.deviation_to_block, 2.0, rep.hausdorff_error + 1e-12);
    EXPECT_NEAR(m.outside_volume, 12.0, 1e-9);
    EXPECT_NEAR(m.outside_distance, 2.0, rep.hausdorff_error + 1e-12);
  }
}

TEST(MeasureMilledShapes, MushroomAndStepDeviations) {
  const Mesh cap = mushroom(), arm = stepped_arm();
  const MilledShapesReport rc = measure(cap, {{&cap, Vec3::UnitZ()}});
  EXPECT_DOUBLE_EQ(rc.blocks[0].filled_volume, 24.0);
  EXPECT_NEAR(rc.blocks[0].deviation, std::sqrt(2.0), rc.hausdorff_error + 1e-12);
  const MilledShapesReport ra = measure(arm, {{&arm, Vec3::UnitZ()}});
  EXPECT_DOUBLE_EQ(ra.blocks[0].filled_volume, 8.0);
  EXPECT_NEAR(ra.blocks[0].deviation, 1.0, ra.hausdorff_error + 1e-12);  // half the gap under the arm
}

TEST(MeasureMilledShapes, DeviationIsToTheInputWhereTheInputIsNearer) {
  // The shelf is one block of an input that also has a ledge [5,6)x[0,2)x[0,1)
  // against the milled wall under the shelf's tip, outside the block: a
  // point of the new base is min(x - 2, 2, 5 - x) from the input, at most 1.5
  // (x = 3.5); the undercut depth stays 2.
  const Mesh block = shelf();
  const Mesh input = union_of_boxes({{{0, 0, 0}, {2, 2, 3}}, {{2, 0, 2}, {5, 2, 3}}, {{5, 0, 0}, {6, 2, 1}}});
  const MilledShapesReport r = measure(input, {{&block, Vec3::UnitZ()}});
  const MilledShapeMeasures& m = r.blocks[0];
  EXPECT_NEAR(m.deviation_to_block, 2.0, r.hausdorff_error + 1e-12);
  EXPECT_NEAR(m.deviation, 1.5, r.hausdorff_error + 1e-12);
  EXPECT_NEAR(m.outside_volume, 12.0, 1e-9);  // the ledge is beside the fill, not in it
  EXPECT_NEAR(m.outside_distance, 1.5, r.hausdorff_error + 1e-12);
}

TEST(MeasureMilledShapes, AMilledShapeCollidingWithABlockUnderItsShelf) {
  // Block 0: the shelf (milled +z); block 1: a box under the shelf's tip,
  // apart from block 0. The blocks do not overlap, their milled shapes do.
  const Mesh a = shelf(), b = box_solid({3, 0, 0}, {5, 2, 1});
  const Mesh input = union_of_boxes({{{0, 0, 0}, {2, 2, 3}}, {{2, 0, 2}, {5, 2, 3}}, {{3, 0, 0}, {5, 2, 1}}});
  const MilledShapesReport r = measure(input, {{&a, Vec3::UnitZ()}, {&b, Vec3::UnitZ()}});
  EXPECT_FALSE(r.blocks[0].exact);
  EXPECT_TRUE(r.blocks[1].exact);
  EXPECT_EQ(r.num_pairs_checked, 1u);
  ASSERT_EQ(r.collisions.size(), 1u);
  EXPECT_EQ(r.collisions[0].a, 0u);
  EXPECT_EQ(r.collisions[0].b, 1u);
  EXPECT_NEAR(r.collisions[0].volume, 4.0, 1e-9);
  EXPECT_NEAR(r.blocks[0].outside_volume, 8.0, 1e-9);  // the fill minus the part that is block 1
  EXPECT_DOUBLE_EQ(r.blocks[0].filled_volume, 12.0);
}

TEST(MeasureMilledShapes, SameResultOnOneThread) {
  // Overlapping in general position (no shared planes), inside a big input.
  const Mesh a = shelf(), b = test::translated(mushroom(), {0.5, 0.25, 0.125}),
             c = test::translated(stepped_arm(), {-0.3, 0.7, 0.2});
  const Mesh input = box_solid({-1, -1, -1}, {10, 10, 10});
  const std::vector<std::pair<const Mesh*, Vec3>> blocks{{&a, Vec3::UnitZ()}, {&b, Vec3::UnitZ()}, {&c, Vec3::UnitZ()}};
  const MilledShapesReport many = measure(input, blocks);
  MilledShapesReport one;
  {
    ThreadLimit limit(1);
    one = measure(input, blocks);
  }
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    EXPECT_EQ(many.blocks[i].volume, one.blocks[i].volume);
    EXPECT_EQ(many.blocks[i].deviation, one.blocks[i].deviation);
    EXPECT_EQ(many.blocks[i].outside_volume, one.blocks[i].outside_volume);
  }
  ASSERT_EQ(many.collisions.size(), one.collisions.size());
  EXPECT_EQ(many.collisions.size(), 3u);
  for (std::size_t k = 0; k < many.collisions.size(); ++k) EXPECT_EQ(many.collisions[k].volume, one.collisions[k].volume);
}

}  // namespace
}  // namespace subfab
