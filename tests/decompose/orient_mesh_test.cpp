// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/orient_mesh.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/fidelity/find_infeasible_features.h"
#include "subfab/geometry/coordinate_rounding.h"
#include "subfab/mesh/read_mesh.h"
#include "support/box_shapes.h"
#include "support/test_support.h"

namespace subfab {
namespace {

//! Closed, outward-oriented axis-aligned box [lo, hi] (12 triangles).
Mesh box_mesh(const Vec3& lo, const Vec3& hi) { return test::make_box_mesh(lo, hi); }

void expect_proper_rotation(const Eigen::Matrix3d& r) {
  EXPECT_NEAR((r * r.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
}

TEST(OrientationEnergy, IsOneForAxisAlignedNormalsAndLargerOtherwise) {
  const Mesh cube = box_mesh(Vec3(0, 0, 0), Vec3(2, 1, 3));
  EXPECT_NEAR(orientation_energy(cube, Eigen::Matrix3d::Identity()), 1.0, 1e-15);
  // Turned 45 degrees about z: the four side faces have ||n||_1 = sqrt(2).
  const Eigen::Matrix3d r = Eigen::AngleAxisd(M_PI / 4, Vec3::UnitZ()).toRotationMatrix();
  const double side = 2 * (2 * 3 + 1 * 3), caps = 2 * 2;
  EXPECT_NEAR(orientation_energy(cube, r), (side * std::sqrt(2.0) + caps) / (side + caps), 1e-12);
  EXPECT_THROW(orientation_energy(Mesh{{Vec3(0, 0, 0), Vec3(1, 0, 0)}, {{0, 0, 1}}}, r), InvalidMeshError);
}

// A box turned by a known rotation is brought back to energy 1 (every normal on an axis).
TEST(OrientMesh, RotatedBoxComesBackToTheAxes) {
  const Mesh box = box_mesh(Vec3(-1, -0.5, -2), Vec3(1, 0.5, 2));
  for (const Eigen::Vector3d& axis_angle : {Eigen::Vector3d(0.3, -0.7, 0.2), Eigen::Vector3d(1.1, 0.4, -0.9),
                                            Eigen::Vector3d(0.0, 0.0, 0.37)}) {
    Mesh turned = box;
    const Eigen::Matrix3d known = Eigen::AngleAxisd(axis_angle.norm(), axis_angle.normalized()).toRotationMatrix();
    transform_mesh(turned, known, Vec3::Zero());
    const OrientResult result = orient_mesh(turned);
    expect_proper_rotation(result.rotation);
    EXPECT_GT(result.energy_before, 1.05);
    EXPECT_NEAR(result.energy_after, 1.0, 1e-8);
    EXPECT_NEAR(orientation_energy(turned, result.rotation), result.energy_after, 1e-14);
    // rotation * known maps the axes to axes: a signed permutation.
    const Eigen::Matrix3d p = result.rotation * known;
    EXPECT_NEAR(p.cwiseAbs().rowwise().maxCoeff().minCoeff(), 1.0, 1e-6);
  }
}

TEST(OrientMesh, AxisAlignedModelsKeepExactlyTheirFrame) {
  const OrientResult cube = orient_mesh(box_mesh(Vec3(0, 0, 0), Vec3(1, 2, 3)));
  EXPECT_EQ(cube.rotation, Eigen::Matrix3d::Identity());
  EXPECT_EQ(cube.energy_after, cube.energy_before);
  EXPECT_NEAR(cube.energy_after, 1.0, 1e-15);
}

// fandisk is a CAD part modelled in its axes (35% of its area has normals
// exactly on an axis): the input frame is near optimal and is kept exactly.
// Without the frame lock, a slightly turned frame has a slightly lower energy.
TEST(OrientMesh, CadPartKeepsItsFrame) {
  const Mesh mesh = read_mesh(test::data_path("fandisk.obj"));
  const OrientResult kept = orient_mesh(mesh);
  EXPECT_EQ(kept.rotation, Eigen::Matrix3d::Identity());
  EXPECT_EQ(kept.energy_after, kept.energy_before);
  const OrientResult free = orient_mesh(mesh, {.min_relative_gain = 0, .keep_frame_area = 1.1});
  expect_proper_rotation(free.rotation);
  EXPECT_LE(free.energy_after, free.energy_before);
  EXPECT_GE(free.energy_after, 1.0);
  EXPECT_GT(free.energy_after, free.energy_before * (1 - 0.02));
  // Turned arbitrarily, it is no longer exactly axis-aligned: orientation
  // brings it back to (about) its original energy.
  Mesh turned = mesh;
  transform_mesh(turned, Eigen::AngleAxisd(0.5, Vec3(3, -1, 2).normalized()).toRotationMatrix(), Vec3::Zero());
  const OrientResult back = orient_mesh(turned);
  EXPECT_LT(back.energy_after, kept.energy_after + 1e-6);
}

TEST(OrientMesh, NeverWorseThanIdentityAndDeterministic) {
  for (const char* name : {"spot.obj", "bunny_lowres.off", "moai.obj"}) {
    Mesh mesh = read_mesh(test::data_path(name));
    // Turn it arbitrarily so the answer is not the identity.
    transform_mesh(mesh, Eigen::AngleAxisd(0.8, Vec3(1, 2, 3).normalized()).toRotationMatrix(), Vec3::Zero());
    const OrientResult a = orient_mesh(mesh);
    expect_proper_rotation(a.rotation);
    EXPECT_LE(a.energy_after, a.energy_before) << name;
    EXPECT_NEAR(a.energy_before, orientation_energy(mesh, Eigen::Matrix3d::Identity()), 1e-14);
    EXPECT_NEAR(a.energy_after, orientation_energy(mesh, a.rotation), 1e-14);
    ASSERT_FALSE(a.candidates[a.chosen].input_frame) << name;
    EXPECT_TRUE(a.infeasible.feasible()) << name;
    // A local check of optimality: no small turn about any axis improves it.
    // (Turned, bunny_lowres's optimum has a cone tip no block can cover; the
    // frame then comes from the feasibility search, which is not a local
    // optimum of E: see SearchesTheCoarseFramesWhenNoCandidateIsFeasible.)
    if (!a.found_by_search) {
      for (int axis = 0; axis < 3; ++axis)
        for (double angle : {-1e-3, 1e-3, -2e-2, 2e-2}) {
          const Eigen::Matrix3d turn = Eigen::AngleAxisd(angle, Vec3::Unit(axis)).toRotationMatrix();
          EXPECT_GE(orientation_energy(mesh, turn * a.rotation), a.energy_after - 1e-9) << name;
        }
    }
    OrientResult serial;
    {
      ThreadLimit one(1);
      serial = orient_mesh(mesh);
    }
    EXPECT_EQ(serial.rotation, a.rotation) << name;
    EXPECT_EQ(serial.energy_after, a.energy_after) << name;
  }
}

// The authors' search: 1000 spherical-Fibonacci directions as the new Z axis
// (shortest turn onto +z, no twist). Searching all three degrees of freedom
// and refining must do at least as well.
TEST(OrientMesh, AtLeastAsGoodAsTheZAxisOnlySearch) {
  for (const char* name : {"bunny_lowres.off", "decimated_knight.off"}) {
    const Mesh mesh = read_mesh(test::data_path(name));
    double best_z_only = INFINITY;
    const int n = 1000;
    for (int i = 0; i < n; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1 - z * z), phi = i * M_PI * (3 - std::sqrt(5.0));
      const Vec3 d(r * std::cos(phi), r * std::sin(phi), z);
      const Eigen::Matrix3d rot = Eigen::Quaterniond::FromTwoVectors(d, Vec3::UnitZ()).toRotationMatrix();
      best_z_only = std::min(best_z_only, orientation_energy(mesh, rot));
    }
    // The search itself (no preference for the input frame, no feasibility check).
    const OrientResult ours = orient_mesh(mesh, {.min_relative_gain = 0, .check_feasibility = false});
    EXPECT_LE(ours.energy_after, best_z_only) << name;
  }
}

// The thesis's moai input is already oriented: the best turn (about half a
// degree) lowers E by less than 0.1%, so the input frame is kept; asking for
// the pure minimum gives that slightly better frame.
TEST(OrientMesh, NegligibleGainKeepsTheInputFrame) {
  const Mesh mesh = read_mesh(test::data_path("moai.obj"));
  const OrientResult kept = orient_mesh(mesh);
  EXPECT_EQ(kept.rotation, Eigen::Matrix3d::Identity());
  const OrientResult pure = orient_mesh(mesh, {.min_relative_gain = 0});
  expect_proper_rotation(pure.rotation);
  EXPECT_LT(pure.energy_after, kept.energy_after);
  EXPECT_GT(pure.energy_after, kept.energy_after * (1 - 1e-3));
}

// A box turned by 1e-4 radians: turning it back lowers E by only about 1e-4
// (relative), far below min_relative_gain, so the input frame ranks first.
// But in its own frame the box cannot be decomposed exactly: at two corners a
// face's corner straddles a coordinate plane (its tilt), so every box holding
// that corner holds the neighbouring faces too (grow_boxes gave up there after
// 8 rounds of refinement). The turned-back frame, with the rounding of the
// turn snapped away, is an exact box: chosen.
TEST(OrientMesh, SlightlyTurnedBoxIsTurnedBackWhenItsFrameIsInfeasible) {
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(1e-4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  Mesh turned = box_mesh(Vec3(-1, -0.5, -2), Vec3(1, 0.5, 2));
  transform_mesh(turned, tilt, Vec3::Zero());
  const OrientResult r = orient_mesh(turned);
  ASSERT_GE(r.candidates.size(), 2u);
  EXPECT_TRUE(r.candidates[0].input_frame);
  EXPECT_EQ(r.candidates[0].num_infeasible, 2);
  EXPECT_EQ(r.chosen, 1u);
  EXPECT_EQ(r.num_rejected, 1u);
  EXPECT_TRUE(r.infeasible.feasible());
  EXPECT_LT(r.energy_after, r.energy_before);
  EXPECT_GT(r.energy_after, r.energy_before * (1 - 1e-3));
  EXPECT_NEAR(r.energy_after, 1.0, 1e-9);
  // rotation * tilt is (about) a signed permutation, and the snapped mesh is an exact box.
  const Eigen::Matrix3d p = r.rotation * tilt;
  EXPECT_NEAR(p.cwiseAbs().rowwise().maxCoeff().minCoeff(), 1.0, 1e-8);
  const Mesh back = rotate_into_frame(turned, r.rotation, OrientOptions{}.snap_tolerance);
  for (int k = 0; k < 3; ++k) {
    std::vector<double> values;
    for (const Vec3& v : back.vertices) values.push_back(v[k]);
    std::sort(values.begin(), values.end());
    EXPECT_EQ(std::unique(values.begin(), values.end()) - values.begin(), 2) << "axis " << k;
  }
  EXPECT_TRUE(find_infeasible_features(back).feasible());
  // Without the feasibility check the input frame is kept, exactly.
  const OrientResult kept = orient_mesh(turned, {.check_feasibility = false});
  EXPECT_EQ(kept.rotation, Eigen::Matrix3d::Identity());
}

TEST(RotateIntoFrame, IdentityIsBitForBitAndSnappingKeepsIds) {
  const Mesh box = box_mesh(Vec3(0, 0, 0), Vec3(1, 2, 3));
  const Mesh same = rotate_into_frame(box, Eigen::Matrix3d::Identity(), 1e-9);
  EXPECT_EQ(same.vertices, box.vertices);
  EXPECT_EQ(same.faces, box.faces);
  // A turn by 90 degrees about z (exactly representable up to cos rounding):
  // coordinates come out exact after snapping.
  const Eigen::Matrix3d quarter = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()).toRotationMatrix();
  const Mesh q = rotate_into_frame(box, quarter, 1e-9);
  EXPECT_EQ(q.faces, box.faces);
  for (std::size_t v = 0; v < box.vertices.size(); ++v)
    EXPECT_NEAR((q.vertices[v] - quarter * box.vertices[v]).norm(), 0.0, 1e-12);
  for (int k = 0; k < 3; ++k) {  // two values per axis: every face exactly axis-aligned
    std::vector<double> values;
    for (const Vec3& v : q.vertices) values.push_back(v[k]);
    std::sort(values.begin(), values.end());
    EXPECT_EQ(std::unique(values.begin(), values.end()) - values.begin(), 2) << "axis " << k;
  }
  EXPECT_TRUE(find_infeasible_features(q).feasible());
}

// Modelled in its axes, with a slanted face: the identity, exactly.
TEST(OrientMesh, AxisAlignedShapesKeepTheIdentityExactly) {
  Mesh tet;
  tet.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  tet.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const Mesh& m : {tet, test::make_l_shape(), test::make_t_shape()}) {
    const OrientResult r = orient_mesh(m);
    EXPECT_EQ(r.rotation, Eigen::Matrix3d::Identity());
    EXPECT_EQ(r.energy_after, r.energy_before);
    EXPECT_TRUE(r.infeasible.feasible());
  }
}

// bunny_lowres: the energy optimum (5.8 degrees away, 0.12% lower) has a cone
// tip no axis-aligned block can cover (grow failed there); the input frame is
// preferred and feasible. Asked for the pure minimum, the optimum is
// rejected for that vertex and a feasible frame is chosen.
TEST(OrientMesh, PrefersFeasibleFrames) {
  const Mesh bunny = read_mesh(test::data_path("bunny_lowres.off"));
  const OrientResult r = orient_mesh(bunny);
  EXPECT_EQ(r.rotation, Eigen::Matrix3d::Identity());
  EXPECT_TRUE(r.infeasible.feasible());
  const OrientResult pure = orient_mesh(bunny, {.min_relative_gain = 0});
  ASSERT_GE(pure.candidates.size(), 2u);
  EXPECT_FALSE(pure.candidates[0].input_frame);
  EXPECT_GT(pure.candidates[0].num_infeasible, 0);
  EXPECT_GE(pure.num_rejected, 1u);
  EXPECT_EQ(pure.candidates[pure.chosen].num_infeasible, 0);
  EXPECT_TRUE(pure.infeasible.feasible());
  for (std::size_t c = 0; c < pure.chosen; ++c) EXPECT_GT(pure.candidates[c].num_infeasible, 0);
  for (std::size_t c = 1; c < pure.candidates.size(); ++c)
    if (!pure.candidates[c].input_frame && !pure.candidates[c - 1].input_frame) {
      EXPECT_LE(pure.candidates[c - 1].energy, pure.candidates[c].energy);
    }
}

// part.off (a CAD part): every energy optimum, and its own frame, has sharp
// oblique creases no axis-aligned block can cover; step 6 searches the
// coarse frames and finds a feasible one (about half of all frames are).
TEST(OrientMesh, SearchesTheCoarseFramesWhenNoCandidateIsFeasible) {
  const Mesh part = read_mesh(test::data_path("part.off"));
  ASSERT_FALSE(find_infeasible_features(part).feasible());
  const OrientResult r = orient_mesh(part);
  EXPECT_TRUE(r.found_by_search);
  EXPECT_GT(r.num_searched, 0u);
  EXPECT_EQ(r.chosen, r.candidates.size() - 1);
  EXPECT_EQ(r.num_rejected, r.candidates.size() - 1);
  for (std::size_t c = 0; c < r.chosen; ++c) EXPECT_GT(r.candidates[c].num_infeasible, 0) << c;
  EXPECT_TRUE(r.infeasible.feasible());
  expect_proper_rotation(r.rotation);
  EXPECT_NEAR(r.energy_after, orientation_energy(part, r.rotation), 1e-12);
  // The frame decompose() builds from it is feasible, exactly.
  EXPECT_TRUE(find_infeasible_features(rotate_into_frame(part, r.rotation, OrientOptions{}.snap_tolerance)).feasible());
  // Same frame with one thread.
  {
    const ThreadLimit one(1);
    EXPECT_EQ(orient_mesh(part).rotation, r.rotation);
  }
  // Without a budget there is no search: the candidate with the fewest features.
  const OrientResult none = orient_mesh(part, {.feasibility_budget = 0});
  EXPECT_FALSE(none.found_by_search);
  EXPECT_EQ(none.num_searched, 0u);
  EXPECT_FALSE(none.infeasible.feasible());
  EXPECT_EQ(none.num_rejected, none.candidates.size());
}

// A six-pointed star prism turned obliquely and written with 6 significant
// digits (data/regression/README.md): its caps are planar and its walls
// perpendicular to them only within the file's rounding, so in the frame
// that aligns it (energy 1.12) the 1e-9 snap leaves hair-tilted faces whose
// creases no axis sees: every candidate was infeasible and it was repaired
// into 76 blocks. Snapped within its own rounding that frame is feasible.
TEST(OrientMesh, AFrameInfeasibleOnlyThroughTheFilesRoundingIsKeptWithThePrecisionSnap) {
  const Mesh star = read_mesh(test::data_path("regression/star_prism_oblique_6digits.off"));
  const OrientResult plain = orient_mesh(star);
  EXPECT_EQ(plain.snap_tolerance, OrientOptions{}.snap_tolerance);
  EXPECT_FALSE(plain.infeasible.feasible());
  OrientOptions o;
  o.precision_snap_tolerance = 4 * coordinate_rounding(star) / bounding_box(star).diagonal();
  ASSERT_GT(o.precision_snap_tolerance, o.snap_tolerance);
  const OrientResult snapped = orient_mesh(star, o);
  EXPECT_TRUE(snapped.infeasible.feasible());
  EXPECT_EQ(snapped.snap_tolerance, o.precision_snap_tolerance);
  EXPECT_EQ(snapped.num_rejected, 0u);
  EXPECT_LT(snapped.energy_after, 1.2);
  EXPECT_LT(snapped.energy_after, plain.energy_after);
  EXPECT_TRUE(find_infeasible_features(rotate_into_frame(star, snapped.rotation, snapped.snap_tolerance)).feasible());
  EXPECT_FALSE(find_infeasible_features(rotate_into_frame(star, snapped.rotation, o.snap_tolerance)).feasible());
  // The precision snap is never used where the default one suffices.
  const Mesh box = box_mesh({0, 0, 0}, {1, 2, 3});
  EXPECT_EQ(orient_mesh(box, o).snap_tolerance, o.snap_tolerance);
}

// fandisk (a CAD part modelled in its axes) turned obliquely and rounded to
// float32, as a binary STL exported at an angle: the energy optimum lies 3
// degrees about x off the frame it was drawn in (0.3% lower energy; 15
// exact blocks there, 6 in the drawn frame); the drawn frame is found from
// its largest flat faces and kept.
TEST(OrientMesh, ACadPartExportedAtAnAngleComesBackToTheFrameItWasDrawnIn) {
  const Mesh fandisk = read_mesh(test::data_path("fandisk.obj"));
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.3, -0.7, 0.5).normalized()).toRotationMatrix();
  Mesh exported = fandisk;
  for (Vec3& v : exported.vertices) {
    const Vec3 t = turn * v;
    for (int k = 0; k < 3; ++k) {
      volatile float f = static_cast<float>(t[k]);  // volatile: -frounding-math may fold the round trip away
      v[k] = f;
    }
  }
  OrientOptions o;
  o.precision_snap_tolerance = 4 * coordinate_rounding(exported) / bounding_box(exported).diagonal();
  const OrientResult r = orient_mesh(exported, o);
  ASSERT_TRUE(r.candidates[r.chosen].design_frame);
  EXPECT_TRUE(r.infeasible.feasible());
  // the drawn frame: rotation x turn is a cube symmetry (a relabelling of the axes)
  const Eigen::Matrix3d back = r.rotation * turn;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_LT(std::min(std::abs(back(i, j)), std::abs(std::abs(back(i, j)) - 1)), 1e-6);
  EXPECT_NEAR(r.energy_after, orientation_energy(fandisk, Eigen::Matrix3d::Identity()), 1e-5);  // float32 normals
  // Without the candidate: the optimum off the drawn frame, lower energy.
  o.design_frame_angle = 0;
  const OrientResult optimum = orient_mesh(exported, o);
  EXPECT_LT(optimum.energy_after, r.energy_after);
  for (const OrientCandidate& c : optimum.candidates) EXPECT_FALSE(c.design_frame);
  // Organic models have no such frame: bunny keeps its own (the candidate, if
  // any, holds no area exactly on the axes and ranks by energy).
  const Mesh bunny = read_mesh(test::data_path("bunny_lowres.off"));
  EXPECT_EQ(orient_mesh(bunny).rotation, Eigen::Matrix3d::Identity());
}

TEST(OrientMesh, RejectsUnusableInput) {
  EXPECT_THROW(orient_mesh(Mesh{}), InvalidMeshError);
  EXPECT_THROW(orient_mesh(box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1)), {.num_twists = 0}), InvalidArgumentError);
  EXPECT_THROW(orient_mesh(box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1)), {.num_candidates = 0}), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
