// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/exact_determinant_signs.h"

#include <CGAL/Exact_rational.h>
#include <gtest/gtest.h>

namespace subfab::detail {
namespace {

using Exact = CGAL::Exact_rational;

TEST(Orient3dSign, ExactOnNearlyCoplanarPoints) {
  const Vec3 a(0.1, 0.2, 0.3), b(0.4, 0.5, 0.6), c(0.7, 0.8, 1.0);
  // p on the line through a and b (in exact arithmetic only approximately).
  for (int k = -3; k <= 3; ++k) {
    const Vec3 p(0.1 + 0.3 * 2, 0.2 + 0.3 * 2 + k * 1e-17, 0.3 + 0.3 * 2);
    const Exact e = (Exact(b.y()) - Exact(a.y())) * (Exact(c.z()) - Exact(a.z())) -
                    (Exact(b.z()) - Exact(a.z())) * (Exact(c.y()) - Exact(a.y()));
    const Exact f = (Exact(b.z()) - Exact(a.z())) * (Exact(c.x()) - Exact(a.x())) -
                    (Exact(b.x()) - Exact(a.x())) * (Exact(c.z()) - Exact(a.z()));
    const Exact g = (Exact(b.x()) - Exact(a.x())) * (Exact(c.y()) - Exact(a.y())) -
                    (Exact(b.y()) - Exact(a.y())) * (Exact(c.x()) - Exact(a.x()));
    const Exact det = e * (Exact(p.x()) - Exact(a.x())) + f * (Exact(p.y()) - Exact(a.y())) +
                      g * (Exact(p.z()) - Exact(a.z()));
    EXPECT_EQ(orient3d_sign(a, b, c, p), CGAL::sign(det));
  }
  EXPECT_EQ(orient3d_sign(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(5, 7, 0)), 0);
  EXPECT_EQ(orient3d_sign(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(5, 7, 1e-300)), 1);
}

}  // namespace
}  // namespace subfab::detail
