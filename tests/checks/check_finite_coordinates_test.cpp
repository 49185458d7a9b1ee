// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_finite_coordinates.h"

#include <gtest/gtest.h>

#include <limits>

#include "support/test_shapes.h"

namespace subfab {
namespace {

TEST(CheckFiniteCoordinates, CubePasses) {
  const CheckResult r = check_finite_coordinates(test::cube());
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(r.name, "finite_coordinates");
  EXPECT_EQ(r.num_offending, 0u);
}

TEST(CheckFiniteCoordinates, NanAndInfinityReportedWithVertexIds) {
  Mesh m = test::cube();
  m.vertices[3].y() = std::numeric_limits<double>::quiet_NaN();
  m.vertices[6].z() = -std::numeric_limits<double>::infinity();
  const CheckResult r = check_finite_coordinates(m);
  EXPECT_TRUE(r.failed());
  EXPECT_EQ(r.num_offending, 2u);
  EXPECT_EQ(r.element, CheckElement::Vertex);
  EXPECT_EQ(r.examples, (std::vector<int>{3, 6}));
  EXPECT_NE(r.message.find("vertex 3"), std::string::npos) << r.message;
}

TEST(CheckFiniteCoordinates, ExamplesAreCapped) {
  Mesh m = test::cube();
  for (auto& p : m.vertices) p.x() = std::numeric_limits<double>::infinity();
  const CheckResult r = check_finite_coordinates(m, {.max_examples = 3});
  EXPECT_EQ(r.num_offending, 8u);
  EXPECT_EQ(r.examples, (std::vector<int>{0, 1, 2}));
}

}  // namespace
}  // namespace subfab
