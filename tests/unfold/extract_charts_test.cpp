// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/extract_charts.h"

#include <gtest/gtest.h>

#include <set>

#include "subfab/mesh/read_mesh.h"
#include "subfab/unfold/build_lattice.h"
#include "subfab/unfold/lattice_directions.h"
#include "subfab/unfold/marching_cubes.h"
#include "support/test_support.h"
#include "support/unfold_test_shapes.h"

namespace subfab {
namespace {

// Every loop vertex lies on its facet's plane, loops[0] turns counter-
// clockwise about the facet normal and holes clockwise; edges pair up.
void expect_valid_poly(const PolyMesh& p, double scale) {
  EXPECT_EQ(count_unpaired_edges(p), 0u);
  const auto& dirs = lattice_directions();
  for (const Facet& f : p.facets) {
    ASSERT_GE(f.normal, 0);
    ASSERT_FALSE(f.loops.empty());
    const auto& d = dirs[static_cast<std::size_t>(f.normal)];
    const Vec3 n = Vec3(d[0], d[1], d[2]).normalized();
    const double offset = n.dot(p.vertices[static_cast<std::size_t>(f.loops[0][0])]);
    for (std::size_t l = 0; l < f.loops.size(); ++l) {
      const auto& loop = f.loops[l];
      ASSERT_GE(loop.size(), 3u);
      Vec3 area = Vec3::Zero();
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const Vec3& a = p.vertices[static_cast<std::size_t>(loop[i])];
        EXPECT_NEAR(n.dot(a), offset, 1e-9 * scale);
        area += a.cross(p.vertices[static_cast<std::size_t>(loop[(i + 1) % loop.size()])]);
      }
      if (l == 0)
        EXPECT_GT(area.dot(n), 0);
      else
        EXPECT_LT(area.dot(n), 0);
    }
  }
}

TEST(ExtractCharts, OnePointGivesAnOctahedron) {
  const Lattice l = test::block_lattice(3, 1, 1);
  const McSurface s = marching_cubes(l);
  const Charts c = extract_charts(s.mesh, s.normals);
  EXPECT_EQ(c.poly.num_facets(), 8u);
  EXPECT_EQ(c.poly.num_vertices(), 6u);
  expect_valid_poly(c.poly, 1);
}

// A 3x3x3 block of inside points: 6 squares, 12 edge bevels, 8 corner
// triangles; the vertices in the middle of the squares' sides are straight
// (two facets) and are dropped, those in the squares' centres are on no
// boundary.
TEST(ExtractCharts, BlockGivesTwentySixFacets) {
  const Lattice l = test::block_lattice(5, 1, 3);
  const McSurface s = marching_cubes(l);
  const Charts c = extract_charts(s.mesh, s.normals);
  EXPECT_EQ(c.poly.num_facets(), 26u);
  EXPECT_EQ(c.poly.num_vertices(), 24u);
  expect_valid_poly(c.poly, 1);
  std::set<int> normals;
  for (const Facet& f : c.poly.facets) normals.insert(f.normal);
  EXPECT_EQ(normals.size(), 26u);
  // Keeping straight vertices keeps the surface closed too.
  const Charts k = extract_charts(s.mesh, s.normals, {.remove_straight_vertices = false});
  EXPECT_EQ(k.poly.num_facets(), 26u);
  EXPECT_EQ(k.poly.num_vertices(), 48u);
  expect_valid_poly(k.poly, 1);
}

// A hollow block (inside shell around an outside cavity): facets with holes
// do not occur, but two components do, the inner one facing inward.
TEST(ExtractCharts, FacetWithAHole) {
  // A 5x5 slab with a hole through its middle: its top face is one facet with a hole.
  Lattice l;
  l.grid.size = {7, 7, 4};
  l.inside.assign(l.grid.num_points(), 0);
  for (int k = 1; k <= 2; ++k)
    for (int j = 1; j <= 5; ++j)
      for (int i = 1; i <= 5; ++i)
        if (!(i == 3 && j == 3)) l.inside[l.grid.index(i, j, k)] = 1;
  const McSurface s = marching_cubes(l);
  const Charts c = extract_charts(s.mesh, s.normals);
  expect_valid_poly(c.poly, 1);
  std::size_t with_holes = 0;
  for (const Facet& f : c.poly.facets) with_holes += f.loops.size() > 1;
  EXPECT_EQ(with_holes, 2u);  // top and bottom
}

TEST(ExtractCharts, RealModelsGiveClosedPlanarFacets) {
  for (const char* name : {"bunny_lowres.off", "fandisk.obj"}) {
    const Mesh m = read_mesh(test::data_path(name));
    const Lattice l = build_lattice(m, {});
    const McSurface s = marching_cubes(l);
    const Charts c = extract_charts(s.mesh, s.normals);
    expect_valid_poly(c.poly, l.grid.spacing);
    EXPECT_GT(c.poly.num_facets(), 50u) << name;
    EXPECT_LT(c.poly.num_facets(), s.mesh.num_faces()) << name;
    ASSERT_EQ(c.face_chart.size(), s.mesh.num_faces());
  }
}

}  // namespace
}  // namespace subfab
