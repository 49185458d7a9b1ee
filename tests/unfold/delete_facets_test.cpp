// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/delete_facets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "subfab/core/error.h"
#include "support/unfold_test_shapes.h"

namespace subfab {
namespace {

using test::box;
using test::chamfered_cube;
using test::corner_cut_cube;
using test::notched_box;

std::set<std::array<double, 3>> vertex_set(const PolyMesh& m) {
  std::set<std::array<double, 3>> s;
  for (const auto& v : m.vertices) s.insert({v.x(), v.y(), v.z()});
  return s;
}

int facet_with_normal(const PolyMesh& m, std::array<int, 3> n) {
  for (std::size_t f = 0; f < m.facets.size(); ++f)
    if (lattice_directions()[m.facets[f].normal] == n) return int(f);
  return -1;
}

TEST(DeleteFacets, ShapesAreValidToStartWith) {
  for (const auto& m : {box(2, 2, 2), chamfered_cube(), corner_cut_cube(), notched_box(), test::l_prism(),
                        test::staircase(), test::bevelled_block()})
    EXPECT_EQ(check_poly_mesh(m, Vec3::Zero(), 1.0), "");
}

TEST(DeleteFacets, ChamferDeletedGivesTheCube) {
  const PolyMesh in = chamfered_cube();
  const int chamfer = facet_with_normal(in, {1, 1, 0});
  ASSERT_GE(chamfer, 0);
  const auto r = delete_facets(in, {.facet_ids = {chamfer}, .grid_step = 1.0});
  EXPECT_TRUE(r.failures.empty());
  EXPECT_EQ(r.num_deleted, 1u);
  EXPECT_EQ(r.mesh.num_facets(), 6u);
  EXPECT_EQ(vertex_set(r.mesh), vertex_set(box(4, 4, 4)));
  EXPECT_EQ(check_poly_mesh(r.mesh, Vec3::Zero(), 1.0), "");
}

TEST(DeleteFacets, CornerTriangleDeletedGivesTheCube) {
  const PolyMesh in = corner_cut_cube();
  const auto r = delete_facets(in, {.facet_ids = {6}, .grid_step = 1.0});
  ASSERT_TRUE(r.failures.empty()) << r.failures[0].reason;
  EXPECT_EQ(r.mesh.num_facets(), 6u);
  EXPECT_EQ(vertex_set(r.mesh), vertex_set(box(4, 4, 4)));
  EXPECT_EQ(check_poly_mesh(r.mesh, Vec3::Zero(), 1.0), "");
}

TEST(DeleteFacets, SmallFacetsGoAutomatically) {
  // chamfer area 4 * sqrt(2) = 5.66 < 6; every other facet is larger.
  const auto r = delete_facets(chamfered_cube(), {.min_facet_area = 6.0, .grid_step = 1.0});
  EXPECT_EQ(r.num_deleted, 1u);
  EXPECT_EQ(r.mesh.num_facets(), 6u);
  // below the chamfer's area: nothing happens
  const auto keep = delete_facets(chamfered_cube(), {.min_facet_area = 5.0, .grid_step = 1.0});
  EXPECT_EQ(keep.num_deleted, 0u);
  EXPECT_EQ(keep.mesh.num_facets(), 7u);
}

TEST(DeleteFacets, CubeFaceCannotBeClosedAndIsKept) {
  const PolyMesh in = box(2, 2, 2);
  const auto r = delete_facets(in, {.facet_ids = {1}, .grid_step = 1.0});
  ASSERT_EQ(r.failures.size(), 1u);
  EXPECT_FALSE(r.failures[0].reason.empty());
  EXPECT_EQ(r.num_deleted, 0u);
  EXPECT_EQ(r.mesh.num_facets(), 6u);
  EXPECT_EQ(vertex_set(r.mesh), vertex_set(in));
  EXPECT_EQ(check_poly_mesh(r.mesh, Vec3::Zero(), 1.0), "");
}

TEST(DeleteFacets, RiserAloneFailsButWithItsTreadCloses) {
  // Figure 3.11: the riser x = 3 has two neighbours with normal +y on different planes.
  const PolyMesh in = notched_box();
  int riser = -1, tread = -1;
  for (std::size_t f = 0; f < in.facets.size(); ++f) {
    const auto& l = in.facets[f].loops[0];
    const auto n = lattice_directions()[in.facets[f].normal];
    if (n == std::array<int, 3>{1, 0, 0} && in.vertices[l[0]].x() == 3) riser = int(f);
    if (n == std::array<int, 3>{0, 1, 0} && in.vertices[l[0]].y() == 3) tread = int(f);
  }
  ASSERT_GE(riser, 0);
  ASSERT_GE(tread, 0);
  const auto alone = delete_facets(in, {.facet_ids = {riser}, .grid_step = 1.0});
  EXPECT_EQ(alone.failures.size(), 1u);
  EXPECT_EQ(alone.mesh.num_facets(), in.num_facets());
  const auto pair = delete_facets(in, {.facet_ids = {riser, tread}, .grid_step = 1.0});
  ASSERT_TRUE(pair.failures.empty()) << pair.failures[0].reason;
  EXPECT_EQ(pair.mesh.num_facets(), 6u);
  EXPECT_EQ(vertex_set(pair.mesh), vertex_set(box(4, 4, 4)));
  // and the automatic pass finds the pair by itself (both are 4 units^2)
  const auto automatic = delete_facets(in, {.min_facet_area = 4.5, .grid_step = 1.0, .group_area_factor = 1.0});
  EXPECT_EQ(automatic.mesh.num_facets(), 6u);
  EXPECT_EQ(check_poly_mesh(automatic.mesh, Vec3::Zero(), 1.0), "");
}

TEST(DeleteFacets, OffsetLatticeFrameIsExact) {
  // Same chamfered cube, scaled by 0.1 and shifted: grid origin/step recover exactness.
  PolyMesh in = chamfered_cube();
  const Vec3 origin(0.3, -1.7, 2.05);
  for (auto& v : in.vertices) v = origin + 0.1 * v;
  const int chamfer = facet_with_normal(in, {1, 1, 0});
  const auto r = delete_facets(in, {.facet_ids = {chamfer}, .grid_origin = origin, .grid_step = 0.1});
  ASSERT_TRUE(r.failures.empty());
  EXPECT_EQ(r.mesh.num_facets(), 6u);
  EXPECT_EQ(check_poly_mesh(r.mesh, origin, 0.1), "");
}

TEST(DeleteFacets, RejectsBadIdsAndOffLatticeVertices) {
  EXPECT_THROW(delete_facets(box(2, 2, 2), {.facet_ids = {17}, .grid_step = 1.0}), InvalidArgumentError);
  PolyMesh off = box(2, 2, 2);
  off.vertices[0].x() += 0.3;  // no longer on the lattice (and not planar)
  EXPECT_THROW(delete_facets(off, {.grid_step = 1.0}), InvalidArgumentError);
}

TEST(CheckPolyMesh, FindsCoplanarNeighboursAndOpenSurfaces) {
  // Cube whose top is split into two coplanar facets.
  std::vector<Vec3> v = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2},
                         {2, 0, 2}, {2, 2, 2}, {0, 2, 2}, {1, 0, 2}, {1, 2, 2}};
  PolyMesh split = test::make_poly(v, {{{0, 3, 2, 1}},
                                       {{4, 8, 9, 7}},
                                       {{8, 5, 6, 9}},
                                       {{0, 1, 5, 8, 4}},
                                       {{2, 3, 7, 9, 6}},
                                       {{0, 4, 7, 3}},
                                       {{1, 2, 6, 5}}});
  EXPECT_NE(check_poly_mesh(split, Vec3::Zero(), 1.0).find("coplanar"), std::string::npos);
  PolyMesh open = box(2, 2, 2);
  open.facets.pop_back();
  EXPECT_NE(check_poly_mesh(open, Vec3::Zero(), 1.0), "");
  // Two cubes overlapping in space: closed and manifold, but intersecting.
  PolyMesh two = box(2, 2, 2);
  const PolyMesh other = box(2, 2, 2);
  const int n = static_cast<int>(two.vertices.size());
  for (const auto& p : other.vertices) two.vertices.push_back(p + Vec3(1, 1, 1));
  for (auto f : other.facets) {
    for (auto& l : f.loops)
      for (int& i : l) i += n;
    two.facets.push_back(f);
  }
  EXPECT_NE(check_poly_mesh(two, Vec3::Zero(), 1.0).find("intersect"), std::string::npos);
  // Apart, they are fine.
  for (int i = n; i < 2 * n; ++i) two.vertices[i] += Vec3(5, 0, 0);
  EXPECT_EQ(check_poly_mesh(two, Vec3::Zero(), 1.0), "");
}

}  // namespace
}  // namespace subfab
