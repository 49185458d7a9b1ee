// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/unfold_nets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "unfold/polygons_overlap.h"
#include "support/unfold_test_shapes.h"

namespace subfab {
namespace {

using unfold_detail::interiors_overlap;
using unfold_detail::Polygon2;

Polygon2 rect(double x0, double y0, double x1, double y1) {
  Polygon2 p;
  p.loops = {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}};
  unfold_detail::update_box(p);
  return p;
}

TEST(PolygonsOverlap, TouchingIsNotOverlapping) {
  EXPECT_FALSE(interiors_overlap(rect(0, 0, 1, 1), rect(1, 0, 2, 1)));   // shared edge
  EXPECT_FALSE(interiors_overlap(rect(0, 0, 1, 1), rect(1, 1, 2, 2)));   // shared corner
  EXPECT_FALSE(interiors_overlap(rect(0, 0, 1, 1), rect(1, 0.5, 2, 3))); // T contact
  EXPECT_FALSE(interiors_overlap(rect(0, 0, 1, 1), rect(3, 3, 4, 4)));
}

TEST(PolygonsOverlap, OverlapsAreFound) {
  EXPECT_TRUE(interiors_overlap(rect(0, 0, 1, 1), rect(0, 0, 1, 1)));          // identical
  EXPECT_TRUE(interiors_overlap(rect(0, 0, 3, 3), rect(1, 1, 2, 2)));          // nested
  EXPECT_TRUE(interiors_overlap(rect(0, 0, 2, 2), rect(1, 1, 3, 3)));          // crossing
  EXPECT_TRUE(interiors_overlap(rect(0, 0, 2, 1), rect(0, 0, 1, 1)));          // shares two sides, inside
  EXPECT_TRUE(interiors_overlap(rect(0, 0, 2, 2), rect(0, 0, 2, 1)));          // all corners on the boundary
  // triangles with the same three corners listed from different starts
  Polygon2 t1, t2;
  t1.loops = {{{0, 0}, {1, 0}, {0, 1}}};
  t2.loops = {{{1, 0}, {0, 1}, {0, 0}}};
  unfold_detail::update_box(t1);
  unfold_detail::update_box(t2);
  EXPECT_TRUE(interiors_overlap(t1, t2));
}

TEST(PolygonsOverlap, HolesAreRespected) {
  Polygon2 ring;
  ring.loops = {{{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {{1, 1}, {1, 3}, {3, 3}, {3, 1}}};
  unfold_detail::update_box(ring);
  EXPECT_FALSE(interiors_overlap(ring, rect(1, 1, 3, 3)));        // fills the hole exactly
  EXPECT_FALSE(interiors_overlap(ring, rect(1.5, 1.5, 2.5, 2.5)));  // inside the hole
  EXPECT_TRUE(interiors_overlap(ring, rect(0.5, 0.5, 1.5, 1.5)));   // across the hole's edge
}

TEST(DihedralAngle, KnownAngles) {
  const PolyMesh cube = test::box(2, 2, 2);
  const auto& top = cube.facets[1].loops[0];
  // the side facet across the top's first edge
  int side = -1;
  for (std::size_t f = 2; f < cube.facets.size(); ++f)
    for (std::size_t i = 0; i < 4; ++i)
      if (cube.facets[f].loops[0][i] == top[1] && cube.facets[f].loops[0][(i + 1) % 4] == top[0]) side = int(f);
  ASSERT_GE(side, 0);
  EXPECT_NEAR(dihedral_angle_deg(cube, 1, side, top[0], top[1]), 90.0, 1e-12);
  const PolyMesh l = test::l_prism();
  // the reflex edge of the L: between sides 2 (y = 2, x 6 -> 2) and 3 (x = 2, y 2 -> 6), at (2, 2)
  // side facet i is edge i of the polygon: facets[2 + i]
  EXPECT_NEAR(dihedral_angle_deg(l, 2 + 2, 2 + 3, 3, 9), 270.0, 1e-12);
  const PolyMesh c = test::chamfered_cube();
  // side 1 (x = 4) and side 2 (chamfer) meet at vertical edge through (4,3): 135 degrees
  EXPECT_NEAR(dihedral_angle_deg(c, 2 + 1, 2 + 2, 2, 7), 135.0, 1e-12);
}

void expect_valid_unfolding(const PolyMesh& mesh, const Unfolding& u) {
  ASSERT_EQ(u.positions.size(), mesh.num_facets());
  std::set<int> seen;
  double total = 0;
  for (const Net& net : u.nets) {
    for (int f : net.facets) {
      EXPECT_TRUE(seen.insert(f).second) << "facet " << f << " in two nets";
      EXPECT_EQ(u.net_of_facet[f], &net - u.nets.data());
    }
    total += net.area;
  }
  EXPECT_EQ(seen.size(), mesh.num_facets());
  EXPECT_EQ(u.folds.size(), mesh.num_facets() - u.nets.size());  // a forest
  EXPECT_EQ(find_net_overlap(u), "");
  Vec3 lo = mesh.vertices[0], hi = lo;
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  EXPECT_LT(refold_error(mesh, u), 1e-9 * (hi - lo).norm());
  // every 2D corner list matches its 3D loop (same sizes)
  for (std::size_t f = 0; f < mesh.num_facets(); ++f) {
    ASSERT_EQ(u.positions[f].size(), mesh.facets[f].loops.size());
    for (std::size_t l = 0; l < mesh.facets[f].loops.size(); ++l)
      EXPECT_EQ(u.positions[f][l].size(), mesh.facets[f].loops[l].size());
  }
}

TEST(UnfoldNets, CubeIsOneNet) {
  const PolyMesh cube = test::box(2, 2, 2);
  const Unfolding u = unfold_nets(cube);
  expect_valid_unfolding(cube, u);
  EXPECT_EQ(u.nets.size(), 1u);
  for (const Fold& f : u.folds) EXPECT_NEAR(f.dihedral_deg, 90.0, 1e-12);
}

TEST(UnfoldNets, SmallSolidsUnfoldAndRefold) {
  for (const PolyMesh& m : {test::chamfered_cube(), test::corner_cut_cube(), test::notched_box(), test::l_prism(),
                            test::staircase(), test::bevelled_block()}) {
    const Unfolding u = unfold_nets(m);
    expect_valid_unfolding(m, u);
    EXPECT_EQ(u.nets.size(), 1u);  // all of these have a one-piece net
  }
}

TEST(UnfoldNets, DetectsABrokenUnfolding) {
  const PolyMesh cube = test::box(2, 2, 2);
  Unfolding u = unfold_nets(cube);
  // Move one non-root facet onto the root: overlap and wrong refold.
  const int moved = u.nets[0].facets[1];
  u.positions[moved] = u.positions[u.nets[0].root];
  EXPECT_NE(find_net_overlap(u), "");
  EXPECT_GT(refold_error(cube, u), 0.1);
}

TEST(UnfoldNets, DeterministicAcrossRuns) {
  const PolyMesh m = test::staircase();
  const Unfolding a = unfold_nets(m), b = unfold_nets(m);
  ASSERT_EQ(a.folds.size(), b.folds.size());
  for (std::size_t i = 0; i < a.folds.size(); ++i) {
    EXPECT_EQ(a.folds[i].parent, b.folds[i].parent);
    EXPECT_EQ(a.folds[i].child, b.folds[i].child);
  }
  EXPECT_EQ(a.positions, b.positions);
}

}  // namespace
}  // namespace subfab
