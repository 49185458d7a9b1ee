// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/triangle_meets_open_box.h"

#include <CGAL/Exact_rational.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace subfab::detail {
namespace {

using Exact = CGAL::Exact_rational;
using ExactPoint = std::array<Exact, 3>;

//! Brute force, independent of the separating-axis test: clip the triangle
//! by the six closed half-spaces of the box with exact rationals; the closed
//! triangle meets the open box iff the clipped polygon is non-empty and, for
//! each of the six constraints, some vertex satisfies it strictly (then the
//! average of the vertices satisfies all six strictly).
bool brute_force_meets(const Vec3& a, const Vec3& b, const Vec3& c, const Box3& box) {
  std::vector<ExactPoint> poly;
  for (const Vec3* v : {&a, &b, &c}) poly.push_back({Exact((*v)[0]), Exact((*v)[1]), Exact((*v)[2])});
  for (int k = 0; k < 3; ++k) {
    for (int sign : {+1, -1}) {
      const Exact value(sign > 0 ? box.min[k] : box.max[k]);
      std::vector<ExactPoint> out;
      const std::size_t n = poly.size();
      for (std::size_t m = 0; m < n; ++m) {
        const ExactPoint& p = poly[m];
        const ExactPoint& q = poly[(m + 1) % n];
        const Exact dp = sign > 0 ? p[k] - value : value - p[k];
        const Exact dq = sign > 0 ? q[k] - value : value - q[k];
        if (dp >= 0) out.push_back(p);
        if ((dp >= 0) != (dq >= 0)) {
          const Exact t = dp / (dp - dq);
          ExactPoint x;
          for (int d = 0; d < 3; ++d) x[d] = p[d] + t * (q[d] - p[d]);
          out.push_back(x);
        }
      }
      poly = std::move(out);
      if (poly.empty()) return false;
    }
  }
  for (int k = 0; k < 3; ++k) {
    bool above_min = false, below_max = false;
    for (const ExactPoint& p : poly) {
      if (p[k] > Exact(box.min[k])) above_min = true;
      if (p[k] < Exact(box.max[k])) below_max = true;
    }
    if (!above_min || !below_max) return false;
  }
  return true;
}

Box3 make_box(const Vec3& p, const Vec3& q) { return Box3{p.cwiseMin(q), p.cwiseMax(q)}; }

TEST(TriangleMeetsOpenBox, HandPickedContacts) {
  const Box3 unit{Vec3(0, 0, 0), Vec3(1, 1, 1)};
  // Triangle in the plane of a box face: touches only the boundary.
  EXPECT_FALSE(triangle_meets_open_box(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1), unit));
  // The same triangle slightly lower crosses the interior.
  EXPECT_TRUE(triangle_meets_open_box(Vec3(0, 0, 0.5), Vec3(1, 0, 0.5), Vec3(0, 1, 0.5), unit));
  // Touching a box edge from outside along a line.
  EXPECT_FALSE(triangle_meets_open_box(Vec3(1, 1, 0), Vec3(1, 1, 1), Vec3(2, 2, 0.5), unit));
  // Touching a box vertex with a triangle vertex.
  EXPECT_FALSE(triangle_meets_open_box(Vec3(1, 1, 1), Vec3(2, 1, 1), Vec3(1, 2, 2), unit));
  // Touching a box vertex with the triangle's interior (plane x+y+z = 3).
  EXPECT_FALSE(triangle_meets_open_box(Vec3(3, 0, 0), Vec3(0, 3, 0), Vec3(0, 0, 3), unit));
  // Slightly deeper: plane x+y+z = 2.9 cuts the corner.
  EXPECT_TRUE(triangle_meets_open_box(Vec3(2.9, 0, 0), Vec3(0, 2.9, 0), Vec3(0, 0, 2.9), unit));
  // Large triangle crossing the whole box; vertices far outside.
  EXPECT_TRUE(triangle_meets_open_box(Vec3(-10, -10, 0.5), Vec3(10, -10, 0.5), Vec3(0, 10, 0.5), unit));
  // Edge-edge separation: triangle whose edge passes just beside a box edge.
  EXPECT_FALSE(triangle_meets_open_box(Vec3(2.5, 0, 0.5), Vec3(0, 2.5, 0.5), Vec3(3, 3, 0.5), unit));
  EXPECT_TRUE(triangle_meets_open_box(Vec3(2.5, 0, 0.5), Vec3(0, 2.5, 0.5), Vec3(0, 0, 0.5), unit));
  // The edge exactly through the box edge x + y = 2 at corner (1,1): touches.
  EXPECT_FALSE(triangle_meets_open_box(Vec3(2, 0, 0.5), Vec3(0, 2, 0.5), Vec3(2, 2, 0.5), unit));
  // Degenerate box (zero extent): never meets.
  EXPECT_FALSE(triangle_meets_open_box(Vec3(-1, -1, 0), Vec3(2, -1, 0), Vec3(0, 2, 0),
                                       Box3{Vec3(0, 0, 0), Vec3(1, 1, 0)}));
}

TEST(TriangleMeetsOpenBox, MatchesExactBruteForceOnIntegerGrids) {
  // Small integer coordinates make contacts (shared planes, edges through
  // corners, vertices on faces) very frequent.
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> coord(0, 4);
  int meets = 0, total = 0;
  for (int iter = 0; iter < 40000; ++iter) {
    Vec3 v[3];
    for (auto& p : v) p = Vec3(coord(rng), coord(rng), coord(rng));
    Box3 box = make_box(Vec3(coord(rng), coord(rng), coord(rng)), Vec3(coord(rng), coord(rng), coord(rng)));
    const bool expected = brute_force_meets(v[0], v[1], v[2], box);
    ASSERT_EQ(triangle_meets_open_box(v[0], v[1], v[2], box), expected)
        << "iteration " << iter << " tri (" << v[0].transpose() << ") (" << v[1].transpose() << ") ("
        << v[2].transpose() << ") box (" << box.min.transpose() << ") (" << box.max.transpose() << ")";
    meets += expected;
    ++total;
  }
  // Both outcomes are well represented.
  EXPECT_GT(meets, total / 20);
  EXPECT_LT(meets, total - total / 20);
}

TEST(TriangleMeetsOpenBox, MatchesExactBruteForceOnNonDyadicAndRandomInputs) {
  // Multiples of 0.1 are not representable: "degenerate" configurations are
  // off by an ulp in either direction, which only exact arithmetic decides.
  std::mt19937 rng(777);
  std::uniform_int_distribution<int> coord(0, 10);
  std::uniform_real_distribution<double> real(-1.0, 2.0);
  for (int iter = 0; iter < 30000; ++iter) {
    Vec3 v[3];
    Box3 box;
    if (iter % 2 == 0) {
      for (auto& p : v) p = Vec3(0.1 * coord(rng), 0.1 * coord(rng), 0.1 * coord(rng));
      box = make_box(Vec3(0.1 * coord(rng), 0.1 * coord(rng), 0.1 * coord(rng)),
                     Vec3(0.1 * coord(rng), 0.1 * coord(rng), 0.1 * coord(rng)));
    } else {
      for (auto& p : v) p = Vec3(real(rng), real(rng), real(rng));
      box = make_box(Vec3(real(rng), real(rng), real(rng)), Vec3(real(rng), real(rng), real(rng)));
    }
    ASSERT_EQ(triangle_meets_open_box(v[0], v[1], v[2], box), brute_force_meets(v[0], v[1], v[2], box))
        << "iteration " << iter;
  }
}

TEST(TriangleMeetsOpenBox, NearlyTouchingByOneUlp) {
  const Box3 unit{Vec3(0, 0, 0), Vec3(1, 1, 1)};
  const double above = std::nextafter(1.0, 2.0);
  const double below = std::nextafter(1.0, 0.0);
  // A sloped triangle whose plane passes one ulp beside the corner (1,1,1).
  for (double offset : {below, 1.0, above}) {
    const Vec3 a(3 * offset, 0, 0), b(0, 3 * offset, 0), c(0, 0, 3 * offset);
    EXPECT_EQ(triangle_meets_open_box(a, b, c, unit), brute_force_meets(a, b, c, unit));
  }
  const Vec3 a(0.3, 0.1, 0.7), b(0.9, 1.7, 0.2), c(-0.4, 0.6, 1.1);
  const Box3 box{Vec3(0.1, 0.2, 0.3), Vec3(0.7, 0.6, 0.5)};
  EXPECT_EQ(triangle_meets_open_box(a, b, c, box), brute_force_meets(a, b, c, box));
}

}  // namespace
}  // namespace subfab::detail
