// SPDX-License-Identifier: GPL-3.0-or-later
// clipped_faces() (surface_deviation.h): the part of a mesh's faces inside a
// closed box, which the fill measure reads instead of whole faces (issue 17).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/surface_deviation.h"

namespace subfab::detail {
namespace {

double area(const Mesh& m) {
  double a = 0;
  for (const Triangle& t : m.faces) {
    const Vec3& p = m.vertices[static_cast<std::size_t>(t[0])];
    a += 0.5 * (m.vertices[static_cast<std::size_t>(t[1])] - p).cross(m.vertices[static_cast<std::size_t>(t[2])] - p).norm();
  }
  return a;
}

Mesh one_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  Mesh m;
  m.vertices = {a, b, c};
  m.faces = {{0, 1, 2}};
  return m;
}

BoundingBox box(const Vec3& lo, const Vec3& hi) {
  BoundingBox b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

TEST(ClippedFaces, ATriangleAcrossACornerOfTheBoxKeepsItsPartInside) {
  // The right triangle (0,0)-(4,0)-(0,4) in z = 0 clipped to [0,1] x [0,1]:
  // the unit square, area 1, every corner inside the closed box.
  const Mesh t = one_triangle({0, 0, 0}, {4, 0, 0}, {0, 4, 0});
  const Mesh c = clipped_faces(t, {0}, box({0, 0, -1}, {1, 1, 1}));
  EXPECT_NEAR(area(c), 1.0, 1e-12);
  for (const Vec3& v : c.vertices)
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(v[k], k == 2 ? -1.0 : 0.0);
      EXPECT_LE(v[k], 1.0);
    }
}

TEST(ClippedFaces, AFaceInsideIsKeptWholeAndAFaceOutsideGivesNothing) {
  const Mesh t = one_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  EXPECT_NEAR(area(clipped_faces(t, {0}, box({-1, -1, -1}, {2, 2, 2}))), 0.5, 1e-15);
  EXPECT_TRUE(clipped_faces(t, {0}, box({2, 2, -1}, {3, 3, 1})).faces.empty());
  // only the listed faces are read
  EXPECT_TRUE(clipped_faces(t, {}, box({-1, -1, -1}, {2, 2, 2})).faces.empty());
}

TEST(ClippedFaces, TheAreaInsideMatchesTheAreaOfTheBoxesPiecesOfATiling) {
  // A long thin triangle (a CAD face) cut by boxes tiling its plane: the
  // clipped areas sum to the triangle's area, whichever the tiling.
  const Mesh t = one_triangle({0, 0, 0}, {10, 0.3, 0.1}, {0.2, 0.5, 0});
  const double whole = area(t);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> cut(0.5, 9.5);
  for (int trial = 0; trial < 20; ++trial) {
    const double x = cut(rng), y = cut(rng) / 20.0;
    double sum = 0;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        sum += area(clipped_faces(t, {0}, box({i ? x : -1, j ? y : -1, -1}, {i ? 11 : x, j ? 1 : y, 1})));
    EXPECT_NEAR(sum, whole, 1e-12 * whole) << trial;
  }
}

}  // namespace
}  // namespace subfab::detail
