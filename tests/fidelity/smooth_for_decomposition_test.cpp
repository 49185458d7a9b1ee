// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/fidelity/smooth_for_decomposition.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/smooth_test_shapes.h"
#include "subfab/checks/check_self_intersections.h"
#include "subfab/checks/require_closed_solid.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/mesh/read_mesh.h"
#include "subfab/mesh/taubin_smooth.h"
#include "support/test_support.h"

namespace subfab {
namespace {

using test::combined;
using test::grid_cube;
using test::icosphere;
using test::inverted;
using test::radial_noise;

//! The deviation report is consistent and bounded by the cap.
void expect_consistent(const SmoothReport& r, double max_deviation) {
  const double cap = max_deviation * r.bbox_diagonal;
  EXPECT_GT(r.bbox_diagonal, 0);
  EXPECT_LE(r.max_displacement, cap);
  EXPECT_LE(r.hausdorff, r.max_displacement);  // the max vertex move bounds the Hausdorff distance
  EXPECT_GE(r.mean_deviation, 0);
  EXPECT_LE(r.mean_deviation, r.hausdorff + r.hausdorff_error);
}

TEST(SmoothForDecomposition, NoisySphereIsSmoothedValidAndMeasured) {
  const Mesh input = radial_noise(icosphere(3), 0.02);
  const SmoothResult result = smooth_for_decomposition(input, {.num_passes = 20, .max_deviation = 0.01});
  const SmoothReport& r = result.report;
  ASSERT_EQ(result.mesh.faces, input.faces);
  ASSERT_EQ(result.mesh.vertices.size(), input.vertices.size());
  expect_consistent(r, 0.01);
  EXPECT_EQ(r.num_passes, 20);
  EXPECT_EQ(r.num_vertices_frozen, 0);
  EXPECT_EQ(r.num_vertices_moved, static_cast<int>(input.vertices.size()));
  EXPECT_GT(r.hausdorff, 0.005);  // the noise (0.02) is largely removed...
  EXPECT_LT(test::radial_rms(result.mesh), 0.5 * test::radial_rms(input));
  EXPECT_NEAR(r.volume / r.input_volume, 1.0, 0.02);  // ...the volume is kept
  Mesh check = result.mesh;
  EXPECT_NO_THROW(require_closed_solid(check));
}

TEST(SmoothForDecomposition, ZeroCapOrZeroPassesChangesNothing) {
  const Mesh input = radial_noise(icosphere(2), 0.02);
  for (const SmoothOptions& o : {SmoothOptions{.num_passes = 0}, SmoothOptions{.max_deviation = 0}}) {
    const SmoothResult result = smooth_for_decomposition(input, o);
    EXPECT_EQ(result.mesh.vertices, input.vertices);
    EXPECT_EQ(result.report.hausdorff, 0);
    EXPECT_EQ(result.report.mean_deviation, 0);
    EXPECT_EQ(result.report.num_vertices_moved, 0);
  }
}

//! A coarse 12-triangle cube floating in a spherical cavity of a ball, its
//! corners close to the cavity's wall (radius 0.953 vs 1). With the
//! displacement cap binding on the shrinking (lambda) step, the inflating
//! (mu) step pushes the cube's corners outwards (to radius ~1.08 at a cap
//! of 0.02 x diagonal): unconstrained, they go through the wall, while the
//! fine spheres barely move.
Mesh cube_in_spherical_cavity() {
  return combined(combined(icosphere(3, 2.0), inverted(icosphere(3, 1.0))), grid_cube(1, 1.1, Vec3(-0.55, -0.55, -0.55)));
}

TEST(SmoothForDecomposition, BacksOffWhereNaiveSmoothingSelfIntersects) {
  const Mesh input = cube_in_spherical_cavity();
  {
    Mesh valid = input;
    ASSERT_NO_THROW(require_closed_solid(valid));
  }
  // The naive filter (same passes, same cap) makes the surface cross itself.
  const double diagonal = bounding_box(input).diagonal();
  Mesh naive = input;
  taubin_smooth(naive, {.num_passes = 10, .max_displacement = 0.02 * diagonal});
  EXPECT_TRUE(check_self_intersections(naive).failed());
  // Ours freezes the offending vertices and stays a valid solid.
  const SmoothResult result = smooth_for_decomposition(input, {.num_passes = 10, .max_deviation = 0.02, .check_every = 1});
  const SmoothReport& r = result.report;
  EXPECT_GT(r.num_vertices_frozen, 0);
  EXPECT_GT(r.num_backoffs, 0);
  EXPECT_GT(r.num_vertices_moved, 600);  // the spheres were still smoothed
  expect_consistent(r, 0.02);
  EXPECT_TRUE(check_self_intersections(result.mesh).passed());
  Mesh check = result.mesh;
  EXPECT_NO_THROW(require_closed_solid(check));
  // Checking every 5 passes backs off to the state 5 passes earlier: also valid.
  const SmoothResult coarse = smooth_for_decomposition(input, {.num_passes = 10, .max_deviation = 0.02, .check_every = 5});
  EXPECT_GT(coarse.report.num_vertices_frozen, 0);
  EXPECT_TRUE(check_self_intersections(coarse.mesh).passed());
}

TEST(SmoothForDecomposition, CavityKeepsItsOrientation) {
  // A cavity's volume is negative; it must stay a cavity (not be mistaken
  // for an inside-out shell).
  const Mesh input = combined(radial_noise(icosphere(3, 2.0), 0.02), inverted(radial_noise(icosphere(3, 1.0), 0.02)));
  const SmoothResult result = smooth_for_decomposition(input, {.num_passes = 20});
  EXPECT_EQ(result.report.num_vertices_frozen, 0);
  EXPECT_NEAR(result.report.volume / result.report.input_volume, 1.0, 0.03);
  Mesh check = result.mesh;
  EXPECT_NO_THROW(require_closed_solid(check));
}

TEST(SmoothForDecomposition, RealModelWithinTheCapAndThreadIndependent) {
  const Mesh input = read_mesh(test::data_path("bunny_lowres.off"));
  const SmoothOptions options{.num_passes = 20, .max_deviation = 0.004};
  SmoothResult one;
  {
    ThreadLimit limit(1);
    one = smooth_for_decomposition(input, options);
  }
  const SmoothResult all = smooth_for_decomposition(input, options);
  EXPECT_EQ(one.mesh.vertices, all.mesh.vertices);
  EXPECT_EQ(one.report.hausdorff, all.report.hausdorff);
  expect_consistent(all.report, 0.004);
  EXPECT_GT(all.report.num_vertices_capped, 0);
  EXPECT_GT(all.report.hausdorff, 0.001 * all.report.bbox_diagonal);
}

TEST(SmoothForDecomposition, RefusesAnOpenMeshAndBadOptions) {
  Mesh open = icosphere(1);
  open.faces.pop_back();
  EXPECT_THROW(smooth_for_decomposition(open, {}), InvalidMeshError);
  const Mesh sphere = icosphere(1);
  EXPECT_THROW(smooth_for_decomposition(sphere, {.max_deviation = -1}), InvalidArgumentError);
  EXPECT_THROW(smooth_for_decomposition(sphere, {.check_every = 0}), InvalidArgumentError);
  EXPECT_THROW(smooth_for_decomposition(sphere, {.mu = -0.2}), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
