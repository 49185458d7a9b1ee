// SPDX-License-Identifier: GPL-3.0-or-later
// PLY reading (src/mesh/read_ply.cpp) on the samples of data/formats/, made
// from real models by scripts/make_format_samples.py (independent of our
// writers) plus hand-written ones.
#include <gtest/gtest.h>

#include "support/mesh_compare.h"
#include "subfab/core/error.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

using test::data_path;

std::filesystem::path sample(const std::string& name) { return data_path("formats") / name; }

TEST(ReadPly, AsciiWithSkippedPropertiesAndElements) {
  const Mesh source = read_mesh(data_path("cross.off"));
  ReadInfo info;
  const Mesh mesh = read_mesh(sample("cross_ascii.ply"), &info);
  EXPECT_EQ(info.format, MeshFormat::Ply);
  EXPECT_EQ(mesh.num_faces(), 76u);
  EXPECT_EQ(mesh.vertices, source.vertices);
  EXPECT_EQ(mesh.faces, source.faces);
}

TEST(ReadPly, BinaryLittleEndianDoubles) {
  const Mesh source = read_mesh(data_path("part.off"));
  const Mesh mesh = read_mesh(sample("part_binary_le.ply"));
  EXPECT_EQ(mesh.num_faces(), 346u);
  EXPECT_EQ(mesh.vertices, source.vertices);
  EXPECT_EQ(mesh.faces, source.faces);
}

TEST(ReadPly, BinaryBigEndianFloatsWithVertexIndexNaming) {
  const Mesh source = read_mesh(data_path("decimated_knight.off"));
  const Mesh mesh = read_mesh(sample("knight_binary_be.ply"));
  EXPECT_EQ(mesh.num_faces(), 1000u);
  ASSERT_EQ(mesh.num_vertices(), source.num_vertices());
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v)
    ASSERT_EQ(mesh.vertices[v], test::to_float(source.vertices[v])) << v;
  EXPECT_EQ(mesh.faces, source.faces);
}

TEST(ReadPly, TriangleStripsWithRestarts) {
  const Mesh source = read_mesh(data_path("part.off"));
  ReadInfo info;
  const Mesh mesh = read_mesh(sample("part_tristrips.ply"), &info);
  EXPECT_EQ(mesh.num_faces(), 346u);
  EXPECT_EQ(mesh.vertices, source.vertices);
  EXPECT_EQ(test::sorted_faces(mesh), test::sorted_faces(source));  // same oriented triangles
}

TEST(ReadPly, HandWrittenStripWithDegenerateJoin) {
  ReadInfo info;
  const Mesh mesh = read_mesh(sample("square_strips.ply"), &info);
  ASSERT_EQ(mesh.num_faces(), 4u);
  EXPECT_EQ(mesh.faces[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(mesh.faces[1], (Triangle{2, 1, 3}));  // odd triangle: winding flipped back
  EXPECT_EQ(mesh.faces[2], (Triangle{4, 5, 6}));  // after the -1 restart
  EXPECT_EQ(mesh.faces[3], (Triangle{6, 5, 7}));
  for (std::size_t f = 0; f < 4; ++f) EXPECT_GT(face_normal_scaled(mesh, f).z(), 0) << f;  // consistent
}

TEST(ReadPly, IntegerCoordinateTypesAndQuads) {
  ReadInfo info;
  const Mesh mesh = read_mesh(sample("cube_int_quads.ply"), &info);
  EXPECT_EQ(mesh.num_vertices(), 8u);
  EXPECT_EQ(mesh.num_faces(), 12u);
  EXPECT_EQ(info.polygons_in_file, 6u);
  EXPECT_EQ(info.polygons_triangulated, 6u);
  EXPECT_EQ(mesh.vertices[6], Vec3(1, 1, 1));
  EXPECT_DOUBLE_EQ(signed_volume(mesh), 1.0);
}

}  // namespace
}  // namespace subfab
