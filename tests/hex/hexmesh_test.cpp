// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/hexmesh.h"

#include <gtest/gtest.h>

#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/exact_mesh.h"

#include "subfab/core/parallel.h"
#include "subfab/hex/scaled_jacobian.h"
#include "subfab/mesh/read_mesh.h"
#include "support/hex_test_shapes.h"
#include "support/test_shapes.h"
#include "support/test_support.h"

namespace subfab {
namespace {

//! Worst scaled Jacobian of the tubular structure (before padding).
double min_of_structure(const HexMeshResult& r) {
  const auto sj = scaled_jacobians(r.structure);
  return *std::min_element(sj.begin(), sj.end());
}

//! The test capsule meshed with skeleton `s` (one split); checks that the
//! result is a valid mesh with no inverted element.
HexMeshResult capsule_with(const Skeleton& s) {
  const Mesh m = test::capsule(1.0, 3.0, 32, 8, 24);
  HexMeshOptions options;
  options.subdivisions = 1;
  HexMeshResult r = hexmesh(m, &s, options);
  EXPECT_TRUE(r.check.valid());
  EXPECT_EQ(r.histogram[0], 0u);
  return r;
}

TEST(Hexmesh, CapsuleIsAValidMeshOnItsSurface) {
  const Mesh m = test::capsule(1.0, 3.0, 32, 8, 24);
  HexMeshOptions options;
  options.subdivisions = 1;
  const HexMeshResult r = hexmesh(m, nullptr, options);
  EXPECT_EQ(r.structure_info.num_cubes, 2u);  // two terminal cubes
  EXPECT_EQ(r.structure_info.num_tubes, 1u);
  EXPECT_TRUE(r.check.valid());
  EXPECT_GT(r.min_sj, 0.3);
  EXPECT_GT(r.avg_sj, 0.6);  // one split only: coarse (0.89 with the automatic two)
  EXPECT_EQ(r.histogram[0], 0u);
  EXPECT_LT(r.mean_distance / r.diagonal, 0.01);
  EXPECT_LT(r.max_distance / r.diagonal, 0.05);
}

// The average pass (raise_mean_scaled_jacobian) runs last: it raises the
// average, the minimum of the final pass stays, and the measures are its
// result; without it, the average is the final pass's. Regression (session
// 32): with boundary vertices sliding 0.25 of their edge the first two sweeps
// lower the capsule's average (.8215 -> .8166 -> .8208), and the pass, which
// stopped after two sweeps that do not raise the best, gave up at the start.
TEST(Hexmesh, AveragePassRaisesTheAverageAndKeepsTheMinimum) {
  const Mesh m = test::capsule(1.0, 3.0, 32, 8, 24);
  HexMeshOptions options;
  options.subdivisions = 1;
  const HexMeshResult r = hexmesh(m, nullptr, options);
  EXPECT_EQ(r.histogram[0], 0u);
  EXPECT_DOUBLE_EQ(r.mean.avg_before, [&] {
    options.raise_mean = false;
    return hexmesh(m, nullptr, options).avg_sj;
  }());
  EXPECT_GT(r.mean.avg_after, r.mean.avg_before + 0.01);
  EXPECT_DOUBLE_EQ(r.avg_sj, r.mean.avg_after);
  EXPECT_GE(r.min_sj, r.raise.min_after);
  EXPECT_DOUBLE_EQ(r.min_sj, r.mean.min_after);
  EXPECT_LT(r.mean_distance / r.diagonal, 0.01);
}

// Resolution control (D.5) on cactus: cones found on terminal branches (the
// trunk and the arm widen more than twice from the small junction cubes),
// the integer programme solved, the parts beyond the cones split once more;
// the result is valid and at most Table D.1's 4K hexahedra (6528 without).
TEST(Hexmesh, CactusWithResolutionControlIsValidWithFewerHexahedra) {
  if (!test::have_shared_models()) GTEST_SKIP() << "no ../shared/models";
  const Mesh m = read_mesh(test::models_path("cactus.off"));
  HexMeshOptions options;
  options.resolution_control = true;
  options.layer_trial = false;  // the mesh with resolution control itself (the trial replaces it on cactus)
  const HexMeshResult r = hexmesh(m, nullptr, options);
  EXPECT_FALSE(r.layer_trial.tried);
  EXPECT_TRUE(r.resolution_control);
  EXPECT_GE(r.cones_found.size(), 1u);
  EXPECT_TRUE(r.resolution.solved);
  EXPECT_EQ(r.resolution.layers.size(), r.cones_found.size());
  EXPECT_EQ(r.subdivisions, r.min_subdivisions + 1);
  EXPECT_TRUE(r.check.valid());
  EXPECT_EQ(r.histogram[0], 0u);
  EXPECT_GT(r.min_sj, 0.3);
  EXPECT_LE(r.mesh.num_hexes(), 4000u);
  EXPECT_GT(std::count_if(r.in_cone_template.begin(), r.in_cone_template.end(), [](int l) { return l >= 0; }), 0);
  EXPECT_LT(r.mean_distance / r.diagonal, 0.005);
  // the boundary's vertices are (almost all) on the surface: their mean
  // distance is a small part of the faces' (the quads' chordal error); the
  // largest, of a vertex the optimiser left off, within the faces' sampled
  // Hausdorff distance (9.1e-5 / 2.2e-3 and 1.1e-2 / 2.7e-2 measured)
  EXPECT_LT(r.mean_vertex_distance, 0.1 * r.mean_distance);
  EXPECT_LE(r.max_vertex_distance, r.max_distance);
}

// The finest level keeping the tubes' layers, without resolution control, on
// cactus: two levels, the second across the tubes only (3488 hexahedra
// against 6528 for two full levels), under Table D.1's 4K with its average
// and minimum beaten (.926 / .620 against .92 / .52), the mean distance
// lower than the resolution-controlled mesh's (1.3e-3 against 2.2e-3 of the
// diagonal). It is the default's result: the layer-keeping trial makes it
// next to the resolution-controlled mesh (2616 hexahedra, .899 / .528) and
// keeps it, being no worse on any measure.
TEST(Hexmesh, CactusDefaultKeepsTheLayersAndBeatsTableD1) {
  if (!test::have_shared_models()) GTEST_SKIP() << "no ../shared/models";
  const Mesh m = read_mesh(test::models_path("cactus.off"));
  const HexMeshResult r = hexmesh(m, nullptr, HexMeshOptions{});
  ASSERT_TRUE(r.layer_trial.tried);
  EXPECT_TRUE(r.layer_trial.kept);
  EXPECT_TRUE(r.keep_layers);
  EXPECT_FALSE(r.resolution_control);
  // the mesh not kept: the resolution-controlled one, worse on average and minimum
  EXPECT_LT(r.layer_trial.hexes, r.mesh.num_hexes());
  EXPECT_LT(r.layer_trial.avg_sj, r.avg_sj);
  EXPECT_LT(r.layer_trial.min_sj, r.min_sj);
  EXPECT_GT(r.layer_trial.mean_distance, r.mean_distance);
  EXPECT_EQ(r.subdivisions, 2);
  EXPECT_GT(r.kept_layer_sheets, 0u);
  EXPECT_TRUE(r.check.valid());
  EXPECT_EQ(r.histogram[0], 0u);
  EXPECT_LE(r.mesh.num_hexes(), 4000u);
  EXPECT_GE(r.avg_sj, 0.92);
  EXPECT_GE(r.min_sj, 0.52);
  EXPECT_LT(r.mean_distance / r.diagonal, 0.0016);
}

// Regression (issue 14, branch hexavg): after branch hexsnap the rocker
// arm's average fell from .911 to .901: the held-vertex stage leaves 139
// hexahedra between the minimum and 0.5 (5 before), at the max-min optimum
// of its patches, and the average pass (floor 0.5) let them only rise, so
// they stayed frozen. With the floor at the held-vertex stage's 0.3 the
// average is .906 (measured; the layer-keeping trial does not win on the
// rocker arm, so it is left out here), the minimum and the vertices on the
// surface as after hexsnap (.3215 / 22 off of 768); with the longer pass and
// a slide of 0.25 (session 32) .911, over Table D.1's .91.
TEST(Hexmesh, RockerArmAverageIsNotFrozenByTheHeldVertices) {
  if (!test::have_shared_models()) GTEST_SKIP() << "no ../shared/models";
  const Mesh m = read_mesh(test::models_path("rocker_arm.obj"));
  HexMeshOptions options;
  options.layer_trial = false;
  const HexMeshResult r = hexmesh(m, nullptr, options);
  EXPECT_TRUE(r.check.valid());
  EXPECT_EQ(r.histogram[0], 0u);
  EXPECT_GE(r.pull.snapped, 80u);  // 93 measured
  EXPECT_GE(r.avg_sj, 0.91);       // .9113 measured (.9063 with a slide of 0.1 and 25 sweeps, .9006 with the floor at 0.5);
                                   // Table D.1: .91
  EXPECT_GE(r.avg_sj, r.mean.avg_before + 0.05);
  EXPECT_GE(r.min_sj, 0.32);       // .3215
  EXPECT_LE(r.vertices_off_surface, 25u);  // 22
  EXPECT_LT(r.mean_vertex_distance / r.diagonal, 1.5e-4);  // 1.26e-4
}

// The average pass goes on while it gains (100 sweeps, a gain of 2e-5 to go
// on): against the same pass stopped after 25 sweeps at a gain of 2e-4 (the
// default until session 32), an average at least as high from the same start,
// the same minimum.
TEST(Hexmesh, TheAveragePassGoesOnWhileItGains) {
  const Mesh m = test::capsule(1.0, 3.0, 32, 8, 24);
  HexMeshOptions options;
  options.subdivisions = 1;
  const HexMeshResult longer = hexmesh(m, nullptr, options);
  options.mean.max_sweeps = 25;
  options.mean.min_gain = 2e-4;
  const HexMeshResult shorter = hexmesh(m, nullptr, options);
  EXPECT_LE(shorter.mean.sweeps, 25);
  EXPECT_GT(longer.mean.sweeps, shorter.mean.sweeps);  // the longer pass really ran longer
  EXPECT_GT(longer.avg_sj, shorter.avg_sj);
  EXPECT_DOUBLE_EQ(longer.mean.avg_before, shorter.mean.avg_before);
  EXPECT_DOUBLE_EQ(longer.mean.min_before, shorter.mean.min_before);
  EXPECT_GE(longer.min_sj, longer.mean.min_before);
}

// The layer-keeping trial on a shape where it loses (the capsule: one tube
// whose layers the trial leaves whole, fewer elements along it): tried, not
// kept, the result the plain one, and the trial's mesh worse on at least one
// of the three measures.
TEST(Hexmesh, LayerTrialIsNotKeptWhenWorse) {
  const Mesh m = test::capsule(1.0, 3.0, 32, 8, 24);
  HexMeshOptions options;
  options.max_hexes = 4000;  // automatic levels under the trial's limit
  const HexMeshResult r = hexmesh(m, nullptr, options);
  HexMeshOptions plain = options;
  plain.layer_trial = false;
  const HexMeshResult p = hexmesh(m, nullptr, plain);
  ASSERT_TRUE(r.layer_trial.tried);
  EXPECT_FALSE(r.layer_trial.kept);
  EXPECT_FALSE(r.keep_layers);
  EXPECT_EQ(r.mesh.num_hexes(), p.mesh.num_hexes());
  EXPECT_DOUBLE_EQ(r.avg_sj, p.avg_sj);
  EXPECT_DOUBLE_EQ(r.min_sj, p.min_sj);
  EXPECT_TRUE(r.layer_trial.avg_sj < r.avg_sj || r.layer_trial.min_sj < r.min_sj ||
              r.layer_trial.mean_distance > r.mean_distance);
}

TEST(Hexmesh, TorusIsARingOfHexahedra) {
  const Mesh m = test::torus(48, 16, 2.0, 0.5);
  HexMeshOptions options;
  options.subdivisions = 1;
  const HexMeshResult r = hexmesh(m, nullptr, options);
  EXPECT_EQ(r.structure_info.num_cubes, 0u);  // a loop with no terminal node
  EXPECT_EQ(r.structure_info.num_tubes, 1u);
  EXPECT_TRUE(r.check.valid());
  EXPECT_GT(r.min_sj, 0.3);
  EXPECT_LT(r.mean_distance / r.diagonal, 0.005);
}

// Regression (issue 14, rocker arm): a ring whose hole (radius 0.5) is
// narrower than its tube (radius 1). D.4's spheres overlap across the hole,
// so the loop kept three samples, and the three straight tubes between them
// cut across the hole: the hex boundary went through it, far from the input
// (rocker arm: max distance 0.17 of the diagonal). The bend criterion of the
// resampling (on loops) splits the loop until its chords follow it.
TEST(Hexmesh, FatRingKeepsItsHoleOpen) {
  const Mesh m = test::torus(64, 24, 1.5, 1.0);
  const Skeleton s = test::ring_skeleton(64, 1.5, 1.0);
  HexMeshOptions options;
  options.subdivisions = 1;
  const HexMeshResult r = hexmesh(m, &s, options);
  EXPECT_GE(r.resampled.num_nodes(), 6u);
  EXPECT_TRUE(r.check.valid());
  EXPECT_EQ(r.histogram[0], 0u);
  const double mean = r.mean_distance / r.diagonal, max = r.max_distance / r.diagonal;
  options.resample.bend_ratio = 0;  // D.4 alone
  const HexMeshResult plain = hexmesh(m, &s, options);
  EXPECT_EQ(plain.resampled.num_nodes(), 3u);
  const double plain_mean = plain.mean_distance / plain.diagonal, plain_max = plain.max_distance / plain.diagonal;
  // measured: 240 hexahedra, distance 9.5e-3 / 2.4e-2 of the diagonal; D.4
  // alone 120, 1.9e-2 / 5.6e-2 (the boundary through the hole)
  EXPECT_LT(mean, 0.013);
  EXPECT_LT(max, 0.035);
  EXPECT_GT(plain_max, 0.045);
  EXPECT_GT(plain_mean, 0.015);
  EXPECT_GT(r.min_sj, plain.min_sj);
}

TEST(Hexmesh, GivenYSkeletonGivesOneBranchCube) {
  // a capsule with a Y skeleton would not fit; a given straight skeleton
  // with an extra inner node is used as it is
  const Mesh m = test::capsule(1.0, 3.0, 32, 8, 24);
  Skeleton s = test::line_skeleton(7, 3.0, 1.0);
  HexMeshOptions options;
  options.subdivisions = 1;
  const HexMeshResult r = hexmesh(m, &s, options);
  EXPECT_EQ(r.skeleton.num_nodes(), 7u);
  EXPECT_TRUE(r.check.valid());
  EXPECT_EQ(r.histogram[0], 0u);
}

//! A Y: the union (exact corefinement) of three capsules of radius r in the
//! xy plane, from near the origin out to `length` at 90, 210 and 330
//! degrees, the arms of test::y_skeleton().
Mesh y_solid(double length = 4.0, double r = 0.5) {
  const double pi = std::numbers::pi;
  detail::ExactMesh solid;
  for (int b = 0; b < 3; ++b) {
    // a capsule along x from -0.25 to length: centre, half length
    const double h = (length + 0.25) / 2;
    Mesh c = test::capsule(r, h - r, 24, 6, 10);
    const double a = pi / 2 + 2 * pi * b / 3;
    for (Vec3& p : c.vertices) {
      const double x = p.x() + h - 0.25;
      p = Vec3(x * std::cos(a) - p.y() * std::sin(a), x * std::sin(a) + p.y() * std::cos(a), p.z());
    }
    detail::ExactMesh e = detail::to_exact(c);
    if (b == 0) solid = e;
    else {
      detail::ExactMesh out;  // not in place (in place, the result depended on earlier tests)
      CGAL::Polygon_mesh_processing::corefine_and_compute_union(solid, e, out);
      solid = std::move(out);
    }
  }
  return detail::to_double(solid);
}

HexMeshResult y_result() {
  // built once (an in-place union gave a solid that depended on the tests
  // run before: the origin outside it, 0.43 from a leftover inner face)
  static const Mesh m = y_solid();
  const Skeleton s = test::y_skeleton(6, 4.0, 0.5);
  HexMeshOptions options;
  options.subdivisions = 1;
  return hexmesh(m, &s, options);
}

TEST(Hexmesh, YJunctionIsConformingWithAClosedQuadBoundary) {
  const HexMeshResult r = y_result();
  EXPECT_EQ(r.structure_info.num_cubes, 4u);  // the branching node and three ends
  EXPECT_EQ(r.structure_info.num_tubes, 3u);
  EXPECT_TRUE(r.check.valid());
  EXPECT_EQ(r.check.num_overshared_quads + r.check.num_same_side_quads + r.check.num_coincident_vertices, 0u);
  EXPECT_EQ(r.check.num_nonmanifold_boundary_edges, 0u);  // closed quad 2-manifold
  EXPECT_GT(r.check.num_boundary_quads, 0u);
  EXPECT_LT(r.mean_distance / r.diagonal, 0.01);
}

// Regression (issue 14): the arms of test::y_skeleton() end on the surface,
// at the tips; the terminal cubes poked out of the surface and their padding
// was inside out (min scaled Jacobian -0.005 after optimisation, 15 of 52
// coarse hexahedra under .05). Terminal nodes are now pulled in along their
// arc and the pillow rays start at the cube centre.
TEST(Hexmesh, YJunctionHasNoInvertedElement) {
  const HexMeshResult r = y_result();
  EXPECT_GT(r.min_sj, 0.2);
  EXPECT_EQ(r.histogram[0], 0u);
  EXPECT_EQ(r.optimize.num_inverted, 0u);
}

// Regression (issue 14): a straight skeleton whose end nodes are the poles
// of the capsule (on the surface) gave 21 inverted hexahedra.
TEST(Hexmesh, SkeletonEndingOnTheSurfaceGivesNoInvertedElement) {
  const Skeleton s = test::line_skeleton(9, 4.0, 1.0);  // from pole to pole
  const HexMeshResult r = capsule_with(s);
  EXPECT_GT(r.min_sj, 0.2);
  // the terminal cubes moved in, off the surface
  for (const Vec3& p : r.structure_info.vertex_anchor) EXPECT_LT(std::abs(p.x()), 3.5);
}

// Regression (issue 14, rocker arm): a skeleton running close to the
// surface (here 0.1 from it, radius 1) gave cubes and sections far smaller
// than the part and 3 inverted hexahedra; its nodes are now moved onto the
// middle of the part first.
TEST(Hexmesh, SkeletonNearTheSurfaceIsCentredFirst) {
  Skeleton s = test::line_skeleton(7, 3.0, 1.0);
  for (Vec3& p : s.points) p.y() = 0.9;
  const HexMeshResult r = capsule_with(s);
  EXPECT_GT(r.min_sj, 0.3);
  for (const Vec3& p : r.structure_info.vertex_anchor) EXPECT_LT(std::abs(p.y()), 0.2);
}

// Regression (issue 14, elephant): terminal nodes outside the surface (0.6
// beyond the poles, radius 0.6, as the skeleton's clean-up leaves a tip) were
// centred onto the surface, capped to a zero radius and gave a cube of size
// 0 (main: 62 inverted hexahedra).
TEST(Hexmesh, TerminalNodesOutsideTheSurfaceGiveFullSizeCubes) {
  Skeleton s = test::line_skeleton(9, 4.6, 1.0);
  s.radii.front() = s.radii.back() = 0.6;
  const HexMeshResult r = capsule_with(s);
  EXPECT_GT(r.min_sj, 0.3);
  EXPECT_GT(min_of_structure(r), 0.3);
}

TEST(Hexmesh, SameOutputWhateverTheThreads) {
  const Mesh m = test::torus(32, 12, 2.0, 0.5);
  HexMeshOptions options;
  options.subdivisions = 1;
  HexMesh one, two;
  {
    ThreadLimit limit(1);
    one = hexmesh(m, nullptr, options).mesh;
  }
  {
    ThreadLimit limit(2);
    two = hexmesh(m, nullptr, options).mesh;
  }
  EXPECT_EQ(one.hexes, two.hexes);
  EXPECT_EQ(one.vertices, two.vertices);
}

}  // namespace
}  // namespace subfab
