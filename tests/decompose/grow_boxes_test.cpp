// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/grow_boxes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <string>

#include "support/box_shapes.h"
#include "geometry/solid_index.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/resolve_overlaps.h"
#include "subfab/decompose/select_cover.h"
#include "subfab/decompose/tolerance_allowances.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

//! The properties every result must have: boxes exactly valid on the
//! returned mesh, seeds covered by their boxes, covered lists exact and
//! sorted, every face covered by some box.
void expect_valid_cover(const GrowResult& r) {
  const detail::SolidIndex index(r.mesh);
  ASSERT_EQ(r.covered.size(), r.boxes.size());
  ASSERT_EQ(r.parent_face.size(), r.mesh.faces.size());
  std::vector<char> covered(r.mesh.faces.size(), 0);
  for (std::size_t i = 0; i < r.boxes.size(); ++i) {
    const HeightBox& hb = r.boxes[i];
    EXPECT_TRUE(index.box_is_valid(hb)) << "box " << i << " axis " << axis_name(hb.axis);
    ASSERT_GE(hb.seed_face, 0);
    EXPECT_TRUE(index.face_covered(hb.seed_face, hb.box, hb.axis)) << "box " << i << " does not cover its seed";
    EXPECT_EQ(r.covered[i], index.faces_covered(hb));
    EXPECT_TRUE(std::is_sorted(r.covered[i].begin(), r.covered[i].end()));
    for (int f : r.covered[i]) covered[static_cast<std::size_t>(f)] = 1;
  }
  EXPECT_EQ(std::count(covered.begin(), covered.end(), 0), 0) << "faces left uncovered";
}

TEST(GrowBoxes, CubeGivesItsOwnBoundingBox) {
  const Mesh cube = test::make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const GrowResult r = grow_boxes(cube, {});
  expect_valid_cover(r);
  EXPECT_EQ(r.num_refined_faces, 0);
  EXPECT_EQ(r.mesh.faces, cube.faces);
  // Every box is the cube itself and covers all 12 faces.
  ASSERT_FALSE(r.boxes.empty());
  for (std::size_t i = 0; i < r.boxes.size(); ++i) {
    EXPECT_EQ(r.boxes[i].box.min, Vec3(0, 0, 0));
    EXPECT_EQ(r.boxes[i].box.max, Vec3(1, 1, 1));
    EXPECT_EQ(r.covered[i].size(), 12u);
  }
}

Mesh l_in_xz() {
  Mesh l = test::make_l_shape();
  for (Vec3& v : l.vertices) std::swap(v.y(), v.z());
  for (Triangle& t : l.faces) std::swap(t[1], t[2]);
  return l;
}

TEST(GrowBoxes, LShapeBoxesAreExactlyValid) {
  const Mesh l = l_in_xz();
  const GrowResult r = grow_boxes(l, {});
  expect_valid_cover(r);
  // Some box is the whole L seen from +z (a valid prism-like block).
  const bool whole = std::any_of(r.boxes.begin(), r.boxes.end(), [](const HeightBox& hb) {
    return hb.axis == Axis::PosZ && hb.box.min == Vec3(0, 0, 0) && hb.box.max == Vec3(2, 1, 2);
  });
  EXPECT_TRUE(whole);
}

// Boxes carried over from an earlier round (decompose() within a
// tolerance, session 35): the whole L along +z is valid and covers every
// face, so it is kept (its seed a face it covers) and no seed is grown; the
// whole L along -z is invalid (the step's top faces +z above the base plane)
// and a box taller than the height limit does not fit: both dropped.
TEST(GrowBoxes, CarriedBoxesAreKeptWhereValidAndNothingIsGrownWhereTheyCover) {
  const Mesh l = l_in_xz();
  const Box3 whole{Vec3(0, 0, 0), Vec3(2, 1, 2)};
  const std::vector<HeightBox> carried{{whole, Axis::PosZ, 7}, {whole, Axis::NegZ, 3}};
  GrowOptions o;
  o.carried = &carried;
  const GrowResult r = grow_boxes(l, o);
  expect_valid_cover(r);
  ASSERT_EQ(r.boxes.size(), 1u);
  EXPECT_EQ(r.boxes[0].axis, Axis::PosZ);
  EXPECT_EQ(r.boxes[0].box.min, whole.min);
  EXPECT_EQ(r.boxes[0].box.max, whole.max);
  EXPECT_EQ(r.num_seeds, 0);
  // Under a height limit of 1.5 the carried box does not fit: grown afresh.
  o.max_height = 1.5;
  const GrowResult limited = grow_boxes(l, o);
  expect_valid_cover(limited);
  EXPECT_GT(limited.num_seeds, 0);
  for (const HeightBox& hb : limited.boxes) {
    const int k = axis_dimension(hb.axis);
    EXPECT_LE(hb.box.max[k] - hb.box.min[k], 1.5) << axis_name(hb.axis);
  }
}

TEST(GrowBoxes, TShapeBoxesAreExactlyValid) {
  Mesh t = test::make_t_shape();
  for (Vec3& v : t.vertices) std::swap(v.y(), v.z());
  for (Triangle& f : t.faces) std::swap(f[1], f[2]);
  const GrowResult r = grow_boxes(t, {});
  expect_valid_cover(r);
  // From -z the whole T is one valid block.
  const bool whole = std::any_of(r.boxes.begin(), r.boxes.end(), [](const HeightBox& hb) {
    return hb.axis == Axis::NegZ && hb.box.min == Vec3(0, 0, 0) && hb.box.max == Vec3(3, 1, 3);
  });
  EXPECT_TRUE(whole);
}

TEST(GrowBoxes, HeightAndMachineLimitsHold) {
  const Mesh mesh = read_mesh(test::data_path("bunny_lowres.off"));
  const double diag = bounding_box(mesh).diagonal();
  GrowOptions options;
  options.max_height = 0.2 * diag;
  options.machine_size = Vec3(0.5 * diag, 0.3 * diag, 1.0 * diag);
  const GrowResult r = grow_boxes(mesh, options);
  expect_valid_cover(r);
  for (const HeightBox& hb : r.boxes) {
    const int ad = axis_dimension(hb.axis);
    const Vec3 size = hb.box.size();
    EXPECT_LE(size[ad], options.max_height);
    const double u = size[(ad + 1) % 3], v = size[(ad + 2) % 3];
    EXPECT_TRUE((u <= 0.5 * diag && v <= 0.3 * diag) || (u <= 0.3 * diag && v <= 0.5 * diag));
  }
}

//! A 1 x 1 x t plate sheared so that its top and bottom are parallel planes
//! z = 0.3 x + 0.3 y (+ t); the side walls stay vertical.
Mesh sheared_plate(double t) {
  Mesh plate = test::make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, t));
  for (Vec3& v : plate.vertices) v.z() += 0.3 * v.x() + 0.3 * v.y();
  return plate;
}

TEST(GrowBoxes, ThinShearedPlateNeedsLocalRefinement) {
  // The bounding box of each big top triangle reaches 0.6 below its highest
  // point: the bottom face (facing away from +z, -x, -y, every axis the top
  // faces) crosses it. 1-to-4 splits shrink the triangles below the
  // plate's thickness and make their boxes valid (thesis 4.3.5).
  const Mesh plate = sheared_plate(0.05);
  GrowOptions options;
  const GrowResult r = grow_boxes(plate, options);
  expect_valid_cover(r);
  EXPECT_GT(r.num_refined_faces, 0);
  EXPECT_GT(r.mesh.faces.size(), plate.faces.size());
  // Refined faces lie in their input faces.
  for (std::size_t f = 0; f < r.mesh.faces.size(); ++f) {
    const Vec3 n = face_unit_normal(r.mesh, f);
    const Vec3 np = face_unit_normal(plate, static_cast<std::size_t>(r.parent_face[f]));
    EXPECT_GT(n.dot(np), 1 - 1e-9);
  }
  options.max_refinement_levels = 0;
  EXPECT_THROW(grow_boxes(plate, options), AlgorithmError);
}

TEST(GrowBoxes, ImpossibleCornerIsReportedNotLeftUncovered) {
  // A thin plate tilted about a diagonal has a convex corner whose three
  // faces no single axis sees (each pair is seen by some axis, not the
  // triple): no box can contain a triangle at that corner, refinement or
  // not. grow_boxes must say so instead of leaving faces uncovered.
  Mesh plate = test::make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 0.03));
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.6, Vec3(1, -1, 0).normalized()).toRotationMatrix();
  transform_mesh(plate, rot, Vec3::Zero());
  GrowOptions options;
  options.max_refinement_levels = 2;
  try {
    grow_boxes(plate, options);
    ADD_FAILURE() << "expected AlgorithmError";
  } catch (const AlgorithmError& e) {
    EXPECT_NE(std::string(e.what()).find("refinement"), std::string::npos) << e.what();
  }
}

TEST(GrowBoxes, ThinFinCreaseFailsAtOnceWithAReason) {
  // A sliver tetrahedron: faces ABC and ABD meet at a ~1 degree fin along
  // the generic edge AB. No axis faces both, so no box can contain AB:
  // refinement cannot help and grow_boxes must say so (not loop 8 levels).
  const Vec3 a(0, 0, 0), b(1, 0.3, 0.2), p(0.3, 0.9, -0.4);
  const Vec3 n = (b - a).cross(p - a).normalized();
  Mesh fin;
  fin.vertices = {a, b, p + 0.01 * n, p - 0.01 * n};
  fin.faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  if (signed_volume(fin) < 0)
    for (Triangle& t : fin.faces) std::swap(t[1], t[2]);
  try {
    grow_boxes(fin, {});
    ADD_FAILURE() << "expected AlgorithmError";
  } catch (const AlgorithmError& e) {
    EXPECT_NE(std::string(e.what()).find("crease"), std::string::npos) << e.what();
  }
}

TEST(GrowBoxes, IdenticalWhateverTheThreadCount) {
  const Mesh mesh = read_mesh(test::data_path("spot.obj"));
  GrowResult one;
  {
    ThreadLimit limit(1);
    one = grow_boxes(mesh, {});
  }
  const GrowResult many = grow_boxes(mesh, {});
  ASSERT_EQ(one.boxes.size(), many.boxes.size());
  for (std::size_t i = 0; i < one.boxes.size(); ++i) {
    EXPECT_EQ(one.boxes[i].axis, many.boxes[i].axis);
    EXPECT_EQ(one.boxes[i].seed_face, many.boxes[i].seed_face);
    EXPECT_EQ(one.boxes[i].box.min, many.boxes[i].box.min);
    EXPECT_EQ(one.boxes[i].box.max, many.boxes[i].box.max);
  }
  EXPECT_EQ(one.covered, many.covered);
}

TEST(GrowBoxes, RefinedFacesParallelToAnAxisDoNotFoolTheFields) {
  // Regression (rotor.off turned 50 deg about x, `decompose --no-orient
  // --tolerance 5e-4`, 2026-12-05: "snap_and_shrink: box 182 (axis +x) is
  // not a valid height box", exit 1). Faces parallel to x were refined;
  // the rounded midpoints tilted some sub-triangles by a hair, so that they
  // face away from +x where their parent did not. The fields, computed on the
  // unrefined mesh, let boxes grow through them. Every box must be exactly
  // valid on the refined mesh.
  const Mesh mesh = read_mesh(test::data_path("regression/rotor_turned_x50.off"));
  ToleranceAllowanceOptions ao;  // decompose's first round
  ao.tolerance = 5e-4 * bounding_box(mesh).diagonal();
  ao.depth_fraction = 2.0;
  const OverhangAllowances allowed = allowances_with_floors(
      mesh, undercut_depths(mesh, ao), std::vector<std::array<std::uint8_t, 3>>(mesh.num_faces(), {0, 0, 0}),
      {2.0, 1.0, 0.5}, ao.tolerance, 0.25);
  GrowOptions o;
  o.allowed_overhangs = &allowed.bits;
  o.overhang_floors = &allowed.floors;
  const GrowResult r = grow_boxes(mesh, o);
  ASSERT_GT(r.num_refined_faces, 0);  // the refinement this is about
  std::vector<std::uint8_t> bits;
  std::vector<std::array<double, 3>> floors;
  for (int parent : r.parent_face) {
    bits.push_back(allowed.bits[static_cast<std::size_t>(parent)]);
    floors.push_back(allowed.floors[static_cast<std::size_t>(parent)]);
  }
  const detail::SolidIndex index(r.mesh, 0.0, &bits, &floors);
  std::size_t invalid = 0;
  for (const HeightBox& hb : r.boxes) invalid += index.box_is_valid(hb) ? 0 : 1;
  EXPECT_EQ(invalid, 0u) << "of " << r.boxes.size() << " boxes";
}

class GrowBoxesOnRealData : public ::testing::TestWithParam<std::string> {};

TEST_P(GrowBoxesOnRealData, EveryFaceCoveredEveryBoxValid) {
  const Mesh mesh = read_mesh(test::data_path(GetParam()));
  const GrowResult r = grow_boxes(mesh, {});
  expect_valid_cover(r);
  EXPECT_LT(r.boxes.size(), mesh.faces.size() / 4) << "boxes should cover many faces each";
}

INSTANTIATE_TEST_SUITE_P(Models, GrowBoxesOnRealData,
                         ::testing::Values("bunny_lowres.off", "fandisk.obj", "spot.obj", "moai.obj"),
                         [](const auto& param_info) {
                           std::string name = param_info.param;
                           for (char& c : name)
                             if (c == '.') c = '_';
                           return name;
                         });

//! The cube [-1, 1]^3 with a square pyramid of height 1.5 standing on each
//! face listed in `spikes` (0: -x, 1: +x, 2: -y, 3: +y, 4: -z, 5: +z).
Mesh spiky_cube(const std::vector<int>& spikes) {
  const Mesh cube = test::make_box_mesh(Vec3(-1, -1, -1), Vec3(1, 1, 1));
  // Quads of make_box_mesh (outward), by the face they lie on.
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  Mesh m;
  m.vertices = cube.vertices;
  for (int q = 0; q < 6; ++q) {
    const int* v = quads[q];
    if (std::find(spikes.begin(), spikes.end(), q) == spikes.end()) {
      m.faces.push_back({v[0], v[1], v[2]});
      m.faces.push_back({v[0], v[2], v[3]});
      continue;
    }
    Vec3 apex = Vec3::Zero();
    apex[q / 2] = (q % 2) ? 2.5 : -2.5;
    const int a = static_cast<int>(m.vertices.size());
    m.vertices.push_back(apex);
    for (int k = 0; k < 4; ++k) m.faces.push_back({v[k], v[(k + 1) % 4], a});
  }
  return m;
}

//! Grow, minimal cover and resolve on a shape: the boxes in carve order.
ResolveResult grow_cover_resolve(const Mesh& mesh) {
  const GrowResult g = grow_boxes(mesh, GrowOptions{});
  expect_valid_cover(g);
  const CoverResult cover = select_cover(g.covered, g.mesh.num_faces(), CoverOptions{});
  EXPECT_TRUE(cover.optimal);
  std::vector<HeightBox> chosen;
  for (int b : cover.selected) chosen.push_back(g.boxes[static_cast<std::size_t>(b)]);
  return resolve_overlaps(g.mesh, chosen, ResolveOptions{});
}

TEST(GrowBoxes, CubeWithOneSpikeIsOneBox) {
  // Everything faces +x or is a side wall for it: one box milled from +x.
  const ResolveResult r = grow_cover_resolve(spiky_cube({1}));
  ASSERT_EQ(r.ordered.size(), 1u);
  EXPECT_EQ(r.ordered[0].axis, Axis::PosX);
  EXPECT_EQ(r.num_splits + r.num_trims, 0);
}

TEST(GrowBoxes, CubeWithOpposedSpikesIsTwoBoxesWithoutSplits) {
  // Spikes on +x and -x: no single axis sees both; two boxes, +x and -x,
  // and an order exists without splitting (the first one carved holds the
  // whole cube).
  const ResolveResult r = grow_cover_resolve(spiky_cube({0, 1}));
  ASSERT_EQ(r.ordered.size(), 2u);
  EXPECT_NE(r.ordered[0].axis, r.ordered[1].axis);
  for (const HeightBox& b : r.ordered) EXPECT_TRUE(b.axis == Axis::PosX || b.axis == Axis::NegX);
  EXPECT_EQ(r.num_splits, 0);
}

}  // namespace
}  // namespace subfab
