// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mesh/taubin_smooth.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/smooth_test_shapes.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

using test::grid_cube;
using test::icosphere;
using test::radial_noise;
using test::radial_rms;

TEST(TaubinSmooth, TestShapesAreClosedOutwardSolids) {
  EXPECT_NEAR(signed_volume(grid_cube(8)), 1.0, 1e-12);
  EXPECT_EQ(grid_cube(8).vertices.size(), 6u * 7 * 7 + 12 * 7 + 8);
  const Mesh sphere = icosphere(3);
  EXPECT_EQ(sphere.vertices.size(), 642u);
  EXPECT_NEAR(signed_volume(sphere), 4.0 / 3.0 * M_PI, 0.05);
}

TEST(TaubinSmooth, CubeFacesStayFlatCornersMoveInward) {
  const int n = 8;
  const Mesh input = grid_cube(n);
  Mesh mesh = input;
  const TaubinReport report = taubin_smooth(mesh, {.num_passes = 1});
  EXPECT_EQ(report.num_passes, 1);
  EXPECT_EQ(report.num_capped, 0);  // no cap
  const Vec3 centre(0.5, 0.5, 0.5);
  int num_interior = 0, num_corners = 0;
  for (std::size_t v = 0; v < input.vertices.size(); ++v) {
    const Vec3& p = input.vertices[v];
    const Vec3& q = mesh.vertices[v];
    int num_on_walls = 0, flat_axis = -1;
    bool deep = true;  // at least 3 grid steps from every cube edge inside its face
    for (int k = 0; k < 3; ++k) {
      if (p[k] == 0 || p[k] == 1) {
        ++num_on_walls;
        flat_axis = k;
      } else {
        const double steps = std::min(p[k], 1 - p[k]) * n;
        deep = deep && steps > 2.5;
      }
    }
    if (num_on_walls == 1 && deep) {
      // One pass = two steps: the corner and edge rounding reaches 2 rings;
      // deeper face vertices stay exactly on their face plane.
      ++num_interior;
      EXPECT_EQ(q[flat_axis], p[flat_axis]) << "vertex " << v;
    }
    if (num_on_walls == 3) {
      ++num_corners;
      EXPECT_LT((q - centre).norm(), (p - centre).norm() - 0.01) << "corner " << v << " not rounded inward";
    }
  }
  EXPECT_EQ(num_interior, 6 * 3 * 3);
  EXPECT_EQ(num_corners, 8);
}

TEST(TaubinSmooth, NoisySphereGetsCloserToTheSphere) {
  const Mesh noisy = radial_noise(icosphere(3), 0.03);
  const double before = radial_rms(noisy);
  EXPECT_GT(before, 0.015);
  for (const TaubinWeights weights : {TaubinWeights::Uniform, TaubinWeights::Cotangent}) {
    Mesh mesh = noisy;
    taubin_smooth(mesh, {.num_passes = 10, .weights = weights});
    // Most of the noise is gone (per-vertex noise also has components below
    // the pass band, which Taubin keeps); the sphere stays (radius within 2%).
    EXPECT_LT(radial_rms(mesh), 0.45 * before) << static_cast<int>(weights);
    EXPECT_NEAR(std::cbrt(signed_volume(mesh) / (4.0 / 3.0 * M_PI)), 1.0, 0.02);
  }
}

TEST(TaubinSmooth, DisplacementCapHoldsExactly) {
  const Mesh input = radial_noise(icosphere(3), 0.03);
  Mesh mesh = input;
  const double cap = 0.004;
  const TaubinReport report = taubin_smooth(mesh, {.num_passes = 10, .max_displacement = cap});
  double largest = 0;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const double d = (mesh.vertices[v] - input.vertices[v]).norm();
    ASSERT_LE(d, cap) << "vertex " << v;  // exact: no tolerance
    largest = std::max(largest, d);
  }
  EXPECT_GT(report.num_capped, 50);  // the cap binds (the noise is 0.03)
  EXPECT_EQ(report.max_displacement, largest);
  EXPECT_GT(largest, 0.999 * cap);
  // Zero cap: nothing moves.
  Mesh still = input;
  taubin_smooth(still, {.num_passes = 3, .max_displacement = 0});
  EXPECT_EQ(still.vertices, input.vertices);
}

TEST(TaubinSmooth, TaubinKeepsTheVolumePlainLaplacianShrinks) {
  const Mesh sphere = icosphere(3);
  const double volume = signed_volume(sphere);
  Mesh taubin = sphere, laplacian = sphere;
  taubin_smooth(taubin, {.num_passes = 10});
  taubin_smooth(laplacian, {.num_passes = 10, .mu = 0});
  // Taubin's transfer function is slightly above 1 below the pass band, so
  // the sphere grows a little (about 1% after 10 passes), far from the
  // plain Laplacian's shrinkage.
  EXPECT_NEAR(signed_volume(taubin) / volume, 1.0, 0.015);
  EXPECT_LT(signed_volume(laplacian) / volume, 0.85);
}

TEST(TaubinSmooth, OnlyTheMovableVerticesMoveAndTheCapUsesTheAnchors) {
  const Mesh input = radial_noise(icosphere(2), 0.05);
  std::vector<int> movable;
  for (int v = 0; v < static_cast<int>(input.vertices.size()); v += 3) movable.push_back(v);
  Mesh mesh = input;
  taubin_smooth(mesh, movable, {.num_passes = 5});
  for (std::size_t v = 0; v < input.vertices.size(); ++v) {
    if (v % 3 == 0)
      EXPECT_NE(mesh.vertices[v], input.vertices[v]) << v;
    else
      EXPECT_EQ(mesh.vertices[v], input.vertices[v]) << v;
  }
  // Two calls of 5 passes with the input as anchors keep the cap measured from
  // the input, not from the positions between the calls.
  const double cap = 0.01;
  Mesh twice = input;
  const TaubinOptions options{.num_passes = 5, .max_displacement = cap, .anchors = input.vertices};
  taubin_smooth(twice, options);
  taubin_smooth(twice, options);
  for (std::size_t v = 0; v < input.vertices.size(); ++v)
    EXPECT_LE((twice.vertices[v] - input.vertices[v]).norm(), cap) << v;
}

TEST(TaubinSmooth, SameResultForAnyThreadCount) {
  const Mesh input = radial_noise(icosphere(4), 0.02);  // 2562 vertices: several parallel chunks
  Mesh one = input, all = input;
  {
    ThreadLimit limit(1);
    taubin_smooth(one, {.num_passes = 4, .weights = TaubinWeights::Cotangent, .max_displacement = 0.01});
  }
  taubin_smooth(all, {.num_passes = 4, .weights = TaubinWeights::Cotangent, .max_displacement = 0.01});
  EXPECT_EQ(one.vertices, all.vertices);
}

TEST(TaubinSmooth, RejectsInvalidOptions) {
  Mesh mesh = icosphere(1);
  EXPECT_THROW(taubin_smooth(mesh, {.lambda = 0}), InvalidArgumentError);
  EXPECT_THROW(taubin_smooth(mesh, {.lambda = 0.5, .mu = -0.4}), InvalidArgumentError);  // mu > -lambda shrinks
  EXPECT_THROW(taubin_smooth(mesh, {.mu = -1.5}), InvalidArgumentError);
  EXPECT_THROW(taubin_smooth(mesh, {.num_passes = -1}), InvalidArgumentError);
  EXPECT_THROW(taubin_smooth(mesh, {.max_displacement = -1}), InvalidArgumentError);
  const std::vector<Vec3> anchors(3, Vec3::Zero());
  EXPECT_THROW(taubin_smooth(mesh, {.anchors = anchors}), InvalidArgumentError);
  const std::vector<int> bad{static_cast<int>(mesh.vertices.size())};
  EXPECT_THROW(taubin_smooth(mesh, bad, {}), InvalidArgumentError);
  EXPECT_EQ(mesh.vertices, icosphere(1).vertices);  // untouched
}

}  // namespace
}  // namespace subfab
