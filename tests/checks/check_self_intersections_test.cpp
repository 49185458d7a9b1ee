// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_self_intersections.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/test_shapes.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

TEST(CheckSelfIntersections, CleanShapesPass) {
  EXPECT_TRUE(check_self_intersections(test::cube()).passed());
  EXPECT_TRUE(check_self_intersections(test::tetrahedron()).passed());
  EXPECT_TRUE(check_self_intersections(test::torus(24, 16)).passed());
}

TEST(CheckSelfIntersections, TwoOverlappingTetrahedra) {
  const Mesh m =
      test::append(test::tetrahedron(), test::tetrahedron(Vec3(0.2, 0.2, 0.2), 1.0));
  const CheckResult r = check_self_intersections(m);
  EXPECT_TRUE(r.failed());
  EXPECT_GT(r.num_offending, 0u);
  for (int f : r.examples) EXPECT_LT(f, 8);
  EXPECT_NE(r.message.find("pairs of faces intersect"), std::string::npos) << r.message;
}

TEST(CheckSelfIntersections, TouchingWithoutSharedVerticesCounts) {
  // Two cubes side by side, each with its own vertices: their x = 1 faces coincide.
  const Mesh touching = test::append(test::cube(), test::cube(Vec3(1, 0, 0)));
  EXPECT_TRUE(check_self_intersections(touching).failed());
  // A gap of one unit in the last place is enough to separate them.
  const Mesh apart =
      test::append(test::cube(), test::cube(Vec3(std::nextafter(1.0, 2.0), 0, 0)));
  EXPECT_TRUE(check_self_intersections(apart).passed());
}

TEST(CheckSelfIntersections, SharedVertexAndEdgeAreNotIntersections) {
  Mesh corner = test::append(test::cube(), test::cube(Vec3(1, 1, 1)));
  weld_identical_vertices(corner);
  EXPECT_TRUE(check_self_intersections(corner).passed());
  // A face folded back onto its neighbour across their shared edge overlaps it.
  Mesh folded;
  folded.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.5, 0.5, 0)};
  folded.faces = {{0, 1, 2}, {1, 0, 3}};
  EXPECT_EQ(check_self_intersections(folded).num_offending, 1u);
  folded.vertices[3] = Vec3(0.5, -0.5, 0);  // unfolded: fine
  EXPECT_TRUE(check_self_intersections(folded).passed());
}

TEST(CheckSelfIntersections, SameResultWithOneThread) {
  const Mesh m = test::append(test::torus(40, 20), test::torus(40, 20, 2.0, 0.5, Vec3(0.3, 0, 0)));
  const CheckResult all = check_self_intersections(m);
  CheckResult one;
  {
    ThreadLimit limit(1);
    one = check_self_intersections(m);
  }
  EXPECT_TRUE(all.failed());
  EXPECT_EQ(all.num_offending, one.num_offending);
  EXPECT_EQ(all.examples, one.examples);
  EXPECT_EQ(all.message, one.message);
}

}  // namespace
}  // namespace subfab
