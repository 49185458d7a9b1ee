// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/scaled_jacobian.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace subfab {
namespace {

std::array<Vec3, 8> unit_cube() {
  return {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
          Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
}

TEST(ScaledJacobian, UnitCubeIsOne) { EXPECT_NEAR(scaled_jacobian(unit_cube()), 1.0, 1e-15); }

TEST(ScaledJacobian, ScaledBoxIsOne) {
  auto p = unit_cube();
  for (auto& v : p) v = Vec3(3 * v.x(), 0.5 * v.y(), 7 * v.z());
  EXPECT_NEAR(scaled_jacobian(p), 1.0, 1e-15);
}

TEST(ScaledJacobian, ShearedCubeIsSinOfTheAngle) {
  const double angle = std::numbers::pi / 3;  // 60 degrees between x and the sheared y edges
  auto p = unit_cube();
  for (auto& v : p) v = Vec3(v.x() + v.y() * std::cos(angle), v.y() * std::sin(angle), v.z());
  EXPECT_NEAR(scaled_jacobian(p), std::sin(angle), 1e-12);
}

TEST(ScaledJacobian, FoldedCornerIsNegative) {
  auto p = unit_cube();
  p[6] = Vec3(0.2, 0.2, 0.2);  // pushed through the opposite corner
  EXPECT_LT(scaled_jacobian(p), 0.0);
  auto q = unit_cube();
  std::swap(q[1], q[3]);  // mirrored: inverted element
  EXPECT_NEAR(scaled_jacobian(q), -1.0, 1e-15);
}

}  // namespace
}  // namespace subfab
