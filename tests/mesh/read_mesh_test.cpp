// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mesh/read_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <string>

#include "mesh/manifest.h"
#include "subfab/core/error.h"
#include "test_support.h"

namespace subfab {
namespace {

using test::data_path;
using test::models_path;

std::filesystem::path write_file(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  return path;
}

//! Reads `bytes` saved as a file named `name` in a fresh temp folder.
Mesh read_bytes(const std::string& name, const std::string& bytes, ReadInfo* info = nullptr) {
  return read_mesh(write_file(test::temp_dir() / name, bytes), info);
}

void expect_indices_valid(const Mesh& mesh) {
  for (const auto& t : mesh.faces)
    for (int v : t) {
      ASSERT_GE(v, 0);
      ASSERT_LT(static_cast<std::size_t>(v), mesh.num_vertices());
    }
}

bool is_mesh_file(const std::filesystem::path& p) {
  static const std::set<std::string> exts = {".obj", ".off", ".ply", ".stl"};
  return exts.count(p.extension().string()) > 0;
}

void expect_matches_manifest(const std::filesystem::path& folder) {
  const auto rows = test::read_manifest(folder / "MANIFEST.md");
  ASSERT_FALSE(rows.empty()) << folder;
  std::set<std::string> listed;
  for (const auto& row : rows) {
    SCOPED_TRACE(row.name);
    listed.insert(row.name);
    ReadInfo info;
    const Mesh mesh = read_mesh(folder / row.name, &info);
    EXPECT_EQ(mesh.num_faces(), row.faces);
    EXPECT_EQ(info.vertices_in_file, row.vertices);
    EXPECT_EQ(mesh.num_vertices(), row.vertices - info.unreferenced_removed);
    expect_indices_valid(mesh);
  }
  // Every mesh file of the folder is in its MANIFEST.
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (!entry.is_regular_file() || !is_mesh_file(entry.path())) continue;
    EXPECT_TRUE(listed.count(entry.path().filename().string())) << entry.path() << " missing from MANIFEST.md";
  }
}

TEST(ReadMesh, EveryDataFileHasItsManifestCounts) { expect_matches_manifest(data_path("")); }

TEST(ReadMesh, AllSharedModelsHaveTheirManifestCounts) {
  if (!test::have_shared_models()) GTEST_SKIP() << "../shared/models is not there";
  const auto rows = test::read_manifest(models_path("MANIFEST.md"));
  EXPECT_EQ(rows.size(), 30u);
  expect_matches_manifest(models_path(""));
}

TEST(ReadMesh, AirplaneDropsItsUnreferencedVertices) {
  if (!test::have_shared_models()) GTEST_SKIP() << "../shared/models is not there";
  ReadInfo info;
  const Mesh mesh = read_mesh(models_path("airplane.obj"), &info);
  EXPECT_EQ(info.unreferenced_removed, 1617u);
  EXPECT_EQ(mesh.num_vertices(), 7017u - 1617u);
  EXPECT_EQ(info.format, MeshFormat::Obj);
}

TEST(ReadMesh, SpotObjFirstVertexAndFace) {
  // data/spot.obj: "v 0.348799 -0.334989 -0.0832331" first, "f 739/1 735/2 736/3" first face.
  const Mesh mesh = read_mesh(data_path("spot.obj"));
  EXPECT_EQ(mesh.vertices[0], Vec3(0.348799, -0.334989, -0.0832331));
  EXPECT_EQ(mesh.faces[0], (Triangle{738, 734, 735}));
}

TEST(ReadObj, AllCornerForms) {
  const std::string text =
      "# comment\r\n"
      "mtllib missing.mtl\r\n"
      "o thing\r\ng group\r\ns 1\r\nusemtl red\r\n"
      "v 0 0 0 1 0 0\r\n"          // colour values
      "v 1 0 0 0.5 0.5 0.5\r\n"
      "v +1 1 0\r\n"
      "v 0 1e0 0\r\n"
      "vt 0 0\r\nvn 0 0 1\r\n"
      "f 1/1/1 2/1/1 3/1/1\r\n"    // v/vt/vn
      "f 1//1 3//1 4//1\r\n"       // v//vn
      "f 1/1 2/1 3/1\r\n"          // v/vt
      "f -4 -3 -2 -1\r\n"          // negative indices, quad
      "f 1 2 \\\r\n 4\r\n";         // line continuation
  ReadInfo info;
  const Mesh mesh = read_bytes("corners.obj", text, &info);
  ASSERT_EQ(mesh.num_vertices(), 4u);
  ASSERT_EQ(mesh.num_faces(), 6u);
  EXPECT_EQ(mesh.vertices[2], Vec3(1, 1, 0));
  EXPECT_EQ(mesh.faces[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(mesh.faces[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(mesh.faces[2], (Triangle{0, 1, 2}));
  EXPECT_EQ(mesh.faces[3], (Triangle{0, 1, 2}));
  EXPECT_EQ(mesh.faces[4], (Triangle{0, 2, 3}));
  EXPECT_EQ(mesh.faces[5], (Triangle{0, 1, 3}));
  EXPECT_EQ(info.polygons_in_file, 5u);
  EXPECT_EQ(info.polygons_triangulated, 1u);
}

TEST(ReadOff, HeaderVariantsAndPolygons) {
  // Counts on the keyword line, comments, a quad with a face colour, COFF
  // vertex colours.
  const std::string text =
      "COFF 5 2 99 # edge count ignored\n"
      "# vertices\n"
      "0 0 0 255 0 0 255\n1 0 0 255 0 0 255\n1 1 0 255 0 0 255\n0 1 0 255 0 0 255\n7 7 7 0 0 0 0\n"
      "\n"
      "4 0 1 2 3 0.5 0.5 0.5\n"
      "3 0 2 1\n";
  ReadInfo info;
  const Mesh mesh = read_bytes("variants.off", text, &info);
  EXPECT_EQ(mesh.num_faces(), 3u);
  EXPECT_EQ(mesh.num_vertices(), 4u);  // the 5th vertex is unreferenced
  EXPECT_EQ(info.vertices_in_file, 5u);
  EXPECT_EQ(info.unreferenced_removed, 1u);
  EXPECT_EQ(info.polygons_triangulated, 1u);
  EXPECT_EQ(mesh.faces[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(mesh.faces[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(mesh.faces[2], (Triangle{0, 2, 1}));

  for (const std::string header : {"OFF\n", "NOFF\n", "STOFF\n", "CNOFF\n", "nOFF\n3\n", ""}) {
    SCOPED_TRACE(header);
    const Mesh m = read_bytes("h.off", header + "3 1\n0 0 0 1 2\n1 0 0 3 4\n0 1 0 5 6\n3 0 1 2\n");
    EXPECT_EQ(m.num_faces(), 1u);
    EXPECT_EQ(m.vertices[1], Vec3(1, 0, 0));
  }
}

}  // namespace
}  // namespace subfab
