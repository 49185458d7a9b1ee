// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/build_lattice.h"

#include <gtest/gtest.h>

#include <cmath>

#include "subfab/geometry/classify_grid_points.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

// Axis-aligned box [lo, hi], outward triangles.
Mesh box_mesh(const Vec3& lo, const Vec3& hi) {
  Mesh m;
  for (int c = 0; c < 8; ++c)
    m.vertices.emplace_back((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
  m.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

// Generalised winding number (sum of solid angles / 4 pi), computed in
// floating point: an independent inside test for points away from the surface.
double solid_angle_winding(const Mesh& m, const Vec3& p) {
  double total = 0;
  for (const auto& f : m.faces) {
    const Vec3 a = m.vertices[static_cast<std::size_t>(f[0])] - p, b = m.vertices[static_cast<std::size_t>(f[1])] - p,
               c = m.vertices[static_cast<std::size_t>(f[2])] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2 * std::atan2(num, den);
  }
  return total / (4 * M_PI);
}

// Grid points exactly on faces, edges and corners of the box [0, 1]^3: the
// symbolic perturbation (e, e^2, e^3) moves each one towards +x, +y, +z, so
// exactly the points with every coordinate in {0, 0.5} are inside.
TEST(ClassifyGridPoints, PointsOnTheSurfaceFollowOneRule) {
  const Mesh m = box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
  GridPoints g;
  g.origin = Vec3(-1, -1, -1);
  g.spacing = 0.5;
  g.size = {7, 7, 7};
  const auto w = classify_grid_points(m, g);
  for (int k = 0; k < 7; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 7; ++i) {
        const auto in = [](int x) { return x == 2 || x == 3; };  // coordinates 0 and 0.5
        EXPECT_EQ(w[g.index(i, j, k)], (in(i) && in(j) && in(k)) ? 1 : 0) << i << " " << j << " " << k;
      }
}

TEST(ClassifyGridPoints, InvertedMeshGivesMinusOne) {
  Mesh m = box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
  for (auto& f : m.faces) std::swap(f[1], f[2]);
  GridPoints g;
  g.origin = Vec3(0.25, 0.25, 0.25);
  g.spacing = 0.5;
  g.size = {2, 2, 2};
  for (int w : classify_grid_points(m, g)) EXPECT_EQ(w, -1);
}

TEST(BuildLattice, BoxSignsAndPadding) {
  const Mesh m = box_mesh(Vec3(0, 0, 0), Vec3(2, 3, 4));
  const Lattice l = build_lattice(m, {.granularity = 0.25});
  const GridPoints& g = l.grid;
  std::size_t expected = 0;
  for (int k = 0; k < g.size[2]; ++k)
    for (int j = 0; j < g.size[1]; ++j)
      for (int i = 0; i < g.size[0]; ++i) {
        const Vec3 p = g.point(i, j, k);
        const bool on_border = i == 0 || j == 0 || k == 0 || i == g.size[0] - 1 || j == g.size[1] - 1 || k == g.size[2] - 1;
        if (on_border) {
          EXPECT_FALSE(l.is_inside(i, j, k));
        }
        // Away from the surface (no ties): plain comparison.
        const bool clearly_in = p.x() > 1e-9 && p.x() < 2 - 1e-9 && p.y() > 1e-9 && p.y() < 3 - 1e-9 && p.z() > 1e-9 &&
                                p.z() < 4 - 1e-9;
        const bool clearly_out = p.x() < -1e-9 || p.x() > 2 + 1e-9 || p.y() < -1e-9 || p.y() > 3 + 1e-9 ||
                                 p.z() < -1e-9 || p.z() > 4 + 1e-9;
        if (clearly_in) {
          EXPECT_TRUE(l.is_inside(i, j, k));
        }
        if (clearly_out) {
          EXPECT_FALSE(l.is_inside(i, j, k));
        }
        expected += clearly_in;
      }
  EXPECT_GE(l.num_inside(), expected);
  EXPECT_GT(expected, 0u);
}

TEST(BuildLattice, RejectsBadOptions) {
  const Mesh m = box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
  EXPECT_THROW(build_lattice(m, {.granularity = 0}), InvalidArgumentError);
  EXPECT_THROW(build_lattice(m, {.granularity = 1e-4, .max_points = 1000}), InvalidArgumentError);
  EXPECT_THROW(build_lattice(Mesh{}, {}), InvalidMeshError);
}

// Real model: exact signs agree with the floating-point solid-angle winding
// number at every lattice point where the latter is unambiguous.
TEST(BuildLattice, BunnySignsAgreeWithSolidAngles) {
  const Mesh m = read_mesh(test::data_path("bunny_lowres.off"));
  const Lattice l = build_lattice(m, {});
  const GridPoints& g = l.grid;
  std::size_t compared = 0, inside = 0;
  for (int k = 0; k < g.size[2]; k += 2)
    for (int j = 0; j < g.size[1]; j += 2)
      for (int i = 0; i < g.size[0]; i += 3) {
        const double w = solid_angle_winding(m, g.point(i, j, k));
        if (std::abs(w - std::round(w)) > 0.05) continue;
        EXPECT_EQ(l.is_inside(i, j, k), std::lround(w) != 0) << i << " " << j << " " << k << " w=" << w;
        ++compared;
        inside += l.is_inside(i, j, k);
      }
  EXPECT_GT(compared, 500u);
  EXPECT_GT(inside, 50u);
}

TEST(BuildLattice, DeterministicWhateverTheThreadCount) {
  const Mesh m = read_mesh(test::data_path("spot.obj"));
  const Lattice a = build_lattice(m, {});
  Lattice b;
  {
    ThreadLimit one(1);
    b = build_lattice(m, {});
  }
  EXPECT_EQ(a.grid.size, b.grid.size);
  EXPECT_EQ(a.inside, b.inside);
  EXPECT_GT(a.num_inside(), 0u);
}

}  // namespace
}  // namespace subfab
