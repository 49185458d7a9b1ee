// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mesh/mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

//! Unit cube [0,1]^3, 8 vertices, 12 outward-oriented triangles.
Mesh unit_cube() {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  // Quads as (a, b, c, d) counter-clockwise seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.faces.push_back({q[0], q[1], q[2]});
    m.faces.push_back({q[0], q[2], q[3]});
  }
  return m;
}

TEST(Mesh, UnitCubeAreaVolumeAndBox) {
  const Mesh cube = unit_cube();
  EXPECT_DOUBLE_EQ(surface_area(cube), 6.0);
  EXPECT_DOUBLE_EQ(signed_volume(cube), 1.0);
  const BoundingBox box = bounding_box(cube);
  EXPECT_EQ(box.min, Vec3(0, 0, 0));
  EXPECT_EQ(box.max, Vec3(1, 1, 1));
  EXPECT_DOUBLE_EQ(box.diagonal(), std::sqrt(3.0));
  EXPECT_FALSE(box.is_empty());
  EXPECT_TRUE(BoundingBox().is_empty());
  for (std::size_t f = 0; f < cube.num_faces(); ++f) EXPECT_DOUBLE_EQ(face_area(cube, f), 0.5);
  EXPECT_EQ(face_unit_normal(cube, 0), Vec3(0, 0, -1));  // bottom face looks down
}

TEST(Mesh, FlippedCubeHasNegativeVolume) {
  Mesh cube = unit_cube();
  for (auto& t : cube.faces) std::swap(t[1], t[2]);
  EXPECT_DOUBLE_EQ(signed_volume(cube), -1.0);
}

TEST(Mesh, VolumeIsTranslationInvariantFarFromTheOrigin) {
  Mesh cube = unit_cube();
  transform_mesh(cube, Eigen::Matrix3d::Identity(), Vec3(1e6, -2e6, 3e6));
  EXPECT_NEAR(signed_volume(cube), 1.0, 1e-9);
}

TEST(Mesh, AverageEdgeLengthCountsEachEdgeOnce) {
  // 12 cube edges of length 1 and 6 face diagonals of length sqrt(2).
  EXPECT_DOUBLE_EQ(average_edge_length(unit_cube()), (12.0 + 6.0 * std::sqrt(2.0)) / 18.0);
  EXPECT_EQ(average_edge_length(Mesh{}), 0.0);
}

TEST(Mesh, DegenerateFaceHasZeroNormal) {
  Mesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)};
  m.faces = {{0, 1, 2}};
  EXPECT_EQ(face_unit_normal(m, 0), Vec3::Zero());
  EXPECT_EQ(face_area(m, 0), 0.0);
}

TEST(Mesh, RemoveUnreferencedVerticesRenumbersFaces) {
  Mesh cube = unit_cube();
  // Interleave unused vertices: new index of cube vertex i is 2i + 1.
  Mesh m;
  for (const auto& p : cube.vertices) {
    m.vertices.push_back(Vec3(9, 9, 9));
    m.vertices.push_back(p);
  }
  for (const auto& t : cube.faces) m.faces.push_back({2 * t[0] + 1, 2 * t[1] + 1, 2 * t[2] + 1});
  EXPECT_EQ(remove_unreferenced_vertices(m), 8u);
  EXPECT_EQ(m.vertices, cube.vertices);
  EXPECT_EQ(m.faces, cube.faces);
  EXPECT_EQ(remove_unreferenced_vertices(m), 0u);
}

TEST(Mesh, WeldIdenticalVerticesMergesOnlyExactCopies) {
  // Triangle soup of the cube (3 corners per face), plus a vertex that is
  // 1 ulp away from a corner and must not be merged.
  const Mesh cube = unit_cube();
  Mesh soup;
  for (const auto& t : cube.faces) {
    const int base = static_cast<int>(soup.vertices.size());
    for (int v : t) soup.vertices.push_back(cube.vertices[static_cast<std::size_t>(v)]);
    soup.faces.push_back({base, base + 1, base + 2});
  }
  soup.vertices.push_back(Vec3(std::nextafter(1.0, 2.0), 1, 1));
  soup.vertices.push_back(Vec3(0, 0, 1));
  soup.vertices.push_back(Vec3(1, 1, 0));
  soup.faces.push_back({36, 37, 38});
  EXPECT_EQ(weld_identical_vertices(soup), 36u + 3u - 9u);
  EXPECT_EQ(soup.num_vertices(), 9u);
  // Same oriented faces as the cube, on welded vertices in first-seen order.
  for (std::size_t f = 0; f < cube.num_faces(); ++f)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(soup.vertices[static_cast<std::size_t>(soup.faces[f][static_cast<std::size_t>(c)])],
                cube.vertices[static_cast<std::size_t>(cube.faces[f][static_cast<std::size_t>(c)])]);
  soup.faces.pop_back();
  remove_unreferenced_vertices(soup);
  EXPECT_DOUBLE_EQ(signed_volume(soup), 1.0);
}

TEST(Mesh, RealModelVolumeAndAreaArePositive) {
  const Mesh knight = read_mesh(test::data_path("decimated_knight.off"));
  EXPECT_GT(signed_volume(knight), 0.0);
  EXPECT_GT(surface_area(knight), 0.0);
  const BoundingBox box = bounding_box(knight);
  for (const auto& p : knight.vertices)
    EXPECT_TRUE((p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all());
}

}  // namespace
}  // namespace subfab
