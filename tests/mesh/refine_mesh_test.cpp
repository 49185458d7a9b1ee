// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mesh/refine_mesh.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <utility>

#include "support/box_shapes.h"
#include "subfab/core/error.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

//! Every directed edge used once and its reverse used once: closed,
//! edge-manifold and consistently oriented.
void expect_closed_oriented(const Mesh& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const Triangle& t : m.faces)
    for (int e = 0; e < 3; ++e) ++directed[{t[e], t[(e + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " used " << count << " times";
    const auto it = directed.find({edge.second, edge.first});
    EXPECT_TRUE(it != directed.end() && it->second == 1) << "edge " << edge.first << "-" << edge.second << " unmatched";
  }
}

TEST(RefineMesh, OneCubeTriangleSplitsIntoFourAndNeighboursIntoTwo) {
  const Mesh cube = test::make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const RefineResult r = refine_mesh(cube, {0});
  EXPECT_EQ(r.num_split_1to4, 1);
  EXPECT_EQ(r.num_split_1to2, 3);
  EXPECT_EQ(r.mesh.faces.size(), 12u + 3u + 3u);
  EXPECT_EQ(r.mesh.vertices.size(), 8u + 3u);
  expect_closed_oriented(r.mesh);
  EXPECT_NEAR(signed_volume(r.mesh), 1.0, 1e-15);
  EXPECT_NEAR(surface_area(r.mesh), 6.0, 1e-14);
  // Input vertices keep their ids; face 0 keeps its id (first child, inside the parent).
  for (std::size_t v = 0; v < 8; ++v) EXPECT_EQ(r.mesh.vertices[v], cube.vertices[v]);
  EXPECT_EQ(r.parent[0], 0);
  EXPECT_DOUBLE_EQ(face_area(r.mesh, 0), face_area(cube, 0) / 4);
  ASSERT_EQ(r.parent.size(), r.mesh.faces.size());
  std::vector<double> area(cube.faces.size(), 0.0);
  for (std::size_t f = 0; f < r.mesh.faces.size(); ++f) area[static_cast<std::size_t>(r.parent[f])] += face_area(r.mesh, f);
  for (std::size_t f = 0; f < cube.faces.size(); ++f) EXPECT_NEAR(area[f], face_area(cube, f), 1e-15);
}

TEST(RefineMesh, AdjacentMarksPropagateToKeepOnlyOneToFourAndOneToTwo) {
  // Marking two faces of the same quad, then a third: every split face is
  // either 1-to-4 or 1-to-2, and the mesh stays closed and oriented.
  const Mesh cube = test::make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const RefineResult r = refine_mesh(cube, {0, 1, 4, 4});
  expect_closed_oriented(r.mesh);
  EXPECT_GE(r.num_split_1to4, 3);
  EXPECT_NEAR(signed_volume(r.mesh), 1.0, 1e-15);
  EXPECT_EQ(r.mesh.faces.size(), 12u + 3u * static_cast<std::size_t>(r.num_split_1to4) +
                                     static_cast<std::size_t>(r.num_split_1to2));
}

TEST(RefineMesh, RandomFacesOfARealMeshStayClosedAndPreserveArea) {
  const Mesh mesh = read_mesh(test::data_path("bunny_lowres.off"));
  std::mt19937 rng(3);
  std::vector<int> faces;
  for (int k = 0; k < 60; ++k) faces.push_back(static_cast<int>(rng() % mesh.faces.size()));
  const RefineResult r = refine_mesh(mesh, faces);
  expect_closed_oriented(r.mesh);
  EXPECT_GE(r.num_split_1to4, 55);
  EXPECT_NEAR(signed_volume(r.mesh), signed_volume(mesh), 1e-12 * std::abs(signed_volume(mesh)));
  std::vector<double> area(mesh.faces.size(), 0.0);
  for (std::size_t f = 0; f < r.mesh.faces.size(); ++f) area[static_cast<std::size_t>(r.parent[f])] += face_area(r.mesh, f);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) EXPECT_NEAR(area[f], face_area(mesh, f), 1e-9 * face_area(mesh, f));
  // Twice is deterministic.
  const RefineResult again = refine_mesh(mesh, faces);
  EXPECT_EQ(again.mesh.faces, r.mesh.faces);
  EXPECT_EQ(again.mesh.vertices, r.mesh.vertices);
}

TEST(RefineMesh, RejectsOutOfRangeFaces) {
  const Mesh cube = test::make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
  EXPECT_THROW(refine_mesh(cube, {12}), InvalidArgumentError);
  EXPECT_THROW(refine_mesh(cube, {-1}), InvalidArgumentError);
  const RefineResult none = refine_mesh(cube, {});
  EXPECT_EQ(none.mesh.faces, cube.faces);
}

}  // namespace
}  // namespace subfab
