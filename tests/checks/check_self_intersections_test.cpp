// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_self_intersections.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "subfab/core/error.h"

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

TEST(CountSelfIntersectionsOf, CountsThePairsHoldingTheGivenFaces) {
  // Two tori crossing: every crossing pair holds one face of each.
  const Mesh a = test::torus(40, 20), b = test::torus(40, 20, 2.0, 0.5, Vec3(0.3, 0, 0));
  const Mesh m = test::append(a, b);
  const std::size_t all = check_self_intersections(m).num_offending;
  ASSERT_GT(all, 0u);
  std::vector<int> first(a.num_faces()), every(m.num_faces());
  for (std::size_t f = 0; f < m.num_faces(); ++f) every[f] = static_cast<int>(f);
  for (std::size_t f = 0; f < a.num_faces(); ++f) first[f] = static_cast<int>(f);
  EXPECT_EQ(count_self_intersections_of(m, every), all);  // pairs inside the set counted once
  EXPECT_EQ(count_self_intersections_of(m, first), all);
  EXPECT_EQ(count_self_intersections_of(m, {}), 0u);
  EXPECT_THROW(count_self_intersections_of(m, {static_cast<int>(m.num_faces())}), InvalidArgumentError);
}

TEST(CountSelfIntersectionsOf, AVertexMovedChangesTheCountOnlyThroughItsFaces) {
  // What single_precision_cleanup relies on: the whole check's count minus the
  // count of a vertex's faces does not depend on where that vertex is.
  Mesh m = test::append(test::torus(40, 20), test::torus(40, 20, 2.0, 0.5, Vec3(0.3, 0, 0)));
  std::size_t checked = 0;
  for (int v = 0; v < static_cast<int>(m.num_vertices()); v += 37) {
    std::vector<int> star;
    for (std::size_t f = 0; f < m.num_faces(); ++f)
      for (const int w : m.faces[f])
        if (w == v) star.push_back(static_cast<int>(f));
    const std::size_t before = check_self_intersections(m).num_offending;
    const std::size_t others = before - count_self_intersections_of(m, star);
    const Vec3 old = m.vertices[static_cast<std::size_t>(v)];
    m.vertices[static_cast<std::size_t>(v)] = old * 1.15 + Vec3(0.05, -0.03, 0.1);
    const std::size_t after = check_self_intersections(m).num_offending;
    EXPECT_EQ(others + count_self_intersections_of(m, star), after) << "vertex " << v;
    if (after != before) ++checked;
    m.vertices[static_cast<std::size_t>(v)] = old;
  }
  EXPECT_GT(checked, 0u);  // some moves did change the count
}

}  // namespace
}  // namespace subfab
