// SPDX-License-Identifier: GPL-3.0-or-later
// drop_cutter() against closed forms and against brute force on random triangles.
#include "subfab/mill/drop_cutter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace subfab {
namespace {

Mesh one_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  Mesh m;
  m.vertices = {a, b, c};
  m.faces = {{0, 1, 2}};
  return m;
}

TEST(DropCutter, FacetEdgeAndVertexContacts) {
  const Tool ball{ToolShape::Ball, 6.0}, flat{ToolShape::Flat, 6.0};
  // Horizontal triangle at z = 2: facet contact inside, both tools at 2.
  const TriangleGrid flat_tri(one_triangle({0, 0, 2}, {20, 0, 2}, {0, 20, 2}), 3.0);
  EXPECT_DOUBLE_EQ(drop_cutter(flat_tri, ball, 5, 5), 2.0);
  EXPECT_DOUBLE_EQ(drop_cutter(flat_tri, flat, 5, 5), 2.0);
  // Far away: the floor.
  EXPECT_DOUBLE_EQ(drop_cutter(flat_tri, ball, 40, 40), 0.0);
  // Vertex contact: (-2, 0) is 2 from the corner (0, 0, 2): ball tip at 2 + sqrt(9 - 4) - 3.
  EXPECT_NEAR(drop_cutter(flat_tri, ball, -2, -1e-9), 2.0 + std::sqrt(5.0) - 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(drop_cutter(flat_tri, flat, -2, -1e-9), 2.0);
  // Edge contact: 1 below the edge y = 0 (x = 10): ball tip at 2 + sqrt(9 - 1) - 3.
  EXPECT_NEAR(drop_cutter(flat_tri, ball, 10, -1), 2.0 + std::sqrt(8.0) - 3.0, 1e-9);
  // Inclined plane z = 0.5 x: ball tip at plane(p) + r (1/cos - 1); flat at the uphill rim point.
  const TriangleGrid slope(one_triangle({0, -50, 0}, {50, -50, 25}, {0, 50, 0}), 3.0);
  const double cosine = 1.0 / std::sqrt(1.25);
  EXPECT_NEAR(drop_cutter(slope, ball, 10, -20), 5.0 + 3.0 / cosine - 3.0, 1e-9);
  EXPECT_NEAR(drop_cutter(slope, flat, 10, -20), 0.5 * 13.0, 1e-9);
}

//! Brute force: the highest tool position touching some sampled point of the triangle.
double brute_force(const Mesh& m, const Tool& tool, double x, double y) {
  const Vec3 &a = m.vertices[0], &b = m.vertices[1], &c = m.vertices[2];
  double best = 0.0;
  const int n = 300;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const Vec3 p = a + (b - a) * i / n + (c - a) * j / n;
      const double d = std::hypot(p.x() - x, p.y() - y);
      if (d <= tool.radius()) best = std::max(best, p.z() - tool_profile(tool, d));
    }
  return best;
}

TEST(DropCutter, NeverBelowAnyPointOfTheTriangleAndTight) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-5.0, 5.0), h(0.0, 6.0);
  for (const Tool& tool : {Tool{ToolShape::Ball, 6.0}, Tool{ToolShape::Flat, 8.0}})
    for (int k = 0; k < 60; ++k) {
      const Mesh m = one_triangle({u(rng), u(rng), h(rng)}, {u(rng), u(rng), h(rng)}, {u(rng), u(rng), h(rng)});
      const TriangleGrid grid(m, 2.0);
      const double x = u(rng), y = u(rng);
      const double dc = drop_cutter(grid, tool, x, y), bf = brute_force(m, tool, x, y);
      EXPECT_GE(dc, bf - 1e-9) << "triangle " << k;    // never below a point of the triangle
      EXPECT_LE(dc, bf + 0.05) << "triangle " << k;    // and touching it (up to the sampling)
    }
}

}  // namespace
}  // namespace subfab
