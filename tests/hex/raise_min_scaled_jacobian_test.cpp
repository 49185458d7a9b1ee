// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/raise_min_scaled_jacobian.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "subfab/hex/scaled_jacobian.h"
#include "support/hex_test_shapes.h"
#include "support/test_shapes.h"
#include "support/test_support.h"

namespace subfab {
namespace {

double min_sj(const HexMesh& m) {
  const auto sj = scaled_jacobians(m);
  return *std::min_element(sj.begin(), sj.end());
}

//! n x n x n unit hexahedra filling the cube [0,n]^3; vertex (i,j,k).
struct Grid {
  explicit Grid(int n) : n(n), mesh(test::hex_grid(n, n, n)), surface(test::cube(Vec3::Zero(), n)) {}
  std::size_t id(int i, int j, int k) const { return static_cast<std::size_t>(i + (n + 1) * (j + (n + 1) * k)); }
  int n;
  HexMesh mesh;
  Mesh surface;
};

TEST(RaiseMinScaledJacobian, UntanglesAnInteriorVertexPushedThroughItsNeighbours) {
  Grid g(3);
  g.mesh.vertices[g.id(1, 1, 1)] = Vec3(2.3, 2.2, 2.1);  // beyond (2,2,2): 8 hexahedra around it invert
  ASSERT_LE(min_sj(g.mesh), 0.0);
  const RaiseMinScaledJacobianReport r = raise_min_scaled_jacobian(g.mesh, g.surface);
  EXPECT_GT(r.num_inverted_before, 0u);
  EXPECT_EQ(r.num_inverted_after, 0u);
  EXPECT_GT(r.min_after, 0.02);  // the last resort's margin
  EXPECT_DOUBLE_EQ(r.min_after, min_sj(g.mesh));
  // boundary vertices left the surface by at most a quarter of their edge
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; j <= 3; ++j) EXPECT_NEAR(g.mesh.vertices[g.id(i, j, 3)].z(), 3.0, 0.25 * 1.2);

}

TEST(RaiseMinScaledJacobian, BoundaryVerticesSlideOnTheSurface) {
  Grid g(3);
  const std::size_t v = g.id(1, 1, 3);  // on the top face
  g.mesh.vertices[v] = Vec3(1.35, 1.3, 3.0);   // slid along the face: its hexahedra are skewed
  const double before = min_sj(g.mesh);
  ASSERT_GT(before, 0.0);
  ASSERT_LT(before, 0.6);
  RaiseMinScaledJacobianOptions options;
  options.threshold = 0.9;
  const RaiseMinScaledJacobianReport r = raise_min_scaled_jacobian(g.mesh, g.surface, options);
  EXPECT_GT(r.min_after, before + 0.1);
  EXPECT_NEAR(g.mesh.vertices[v].z(), 3.0, 1e-12);  // still on the top face
  EXPECT_EQ(r.num_off_surface, 0u);
}

TEST(RaiseMinScaledJacobian, GoodMeshIsLeftAlone) {
  Grid g(2);
  const HexMesh before = g.mesh;
  const RaiseMinScaledJacobianReport r = raise_min_scaled_jacobian(g.mesh, g.surface);
  EXPECT_EQ(r.num_moves, 0u);
  EXPECT_EQ(g.mesh.vertices, before.vertices);
  EXPECT_DOUBLE_EQ(r.min_after, 1.0);
}

//! Reads the vertices and hexahedra of a Medit file (as write_hex_mesh writes it).
HexMesh read_medit(const std::filesystem::path& path) {
  std::ifstream in(path);
  HexMesh m;
  std::string token;
  while (in >> token) {
    std::size_t n = 0;
    int ref = 0;
    if (token == "Vertices") {
      in >> n;
      m.vertices.resize(n);
      for (Vec3& v : m.vertices) in >> v.x() >> v.y() >> v.z() >> ref;
    } else if (token == "Hexahedra") {
      in >> n;
      m.hexes.resize(n);
      for (Hex& h : m.hexes) {
        for (int& v : h) in >> v, --v;
        in >> ref;
      }
    }
  }
  return m;
}

// Regression (issue 14, spot): an interior vertex whose star folded over
// (its opposite neighbours on the same side, every corner at it near 0)
// stayed inverted (-1.6e-5, 5 hexahedra): no move of one vertex at a time
// helps and a joint gradient descent on the patch traded those corners for
// new inverted ones. The last resort now also tries the patch with its
// inside reset by Laplacian iterations first. The mesh is the neighbourhood
// of the fold, its own boundary the surface.
TEST(RaiseMinScaledJacobian, FoldedStarIsRepaired) {
  const HexMesh start = read_medit(test::data_path("regression/spot_folded_star.mesh"));
  ASSERT_EQ(start.num_hexes(), 199u);
  Mesh surface = boundary_triangles(start);
  remove_unreferenced_vertices(surface);
  ASSERT_LE(min_sj(start), 0.0);
  HexMesh alone = start;
  RaiseMinScaledJacobianOptions no_repair;
  no_repair.free_boundary_for_inverted = false;
  const RaiseMinScaledJacobianReport a = raise_min_scaled_jacobian(alone, surface, no_repair);
  EXPECT_GT(a.num_inverted_after, 0u);  // one vertex at a time is not enough
  HexMesh m = start;
  const RaiseMinScaledJacobianReport r = raise_min_scaled_jacobian(m, surface);
  EXPECT_EQ(r.num_inverted_after, 0u);
  EXPECT_GT(r.min_after, 0.02);
  EXPECT_TRUE(check_hex_mesh(m).valid());
}

}  // namespace
}  // namespace subfab
