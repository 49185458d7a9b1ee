// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mesh/read_mesh.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>

#include <algorithm>
#include <fstream>
#include <set>
#include <string>

#include "support/manifest.h"
#include "subfab/core/error.h"
#include "support/test_support.h"

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
  // One row per mesh file of the folder (shared/ grows: no fixed count; a
  // parser that drops rows fails here).
  std::size_t num_files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(models_path("")))
    if (entry.is_regular_file() && is_mesh_file(entry.path())) ++num_files;
  EXPECT_GE(rows.size(), 30u);
  EXPECT_EQ(rows.size(), num_files);
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

TEST(ReadObj, SkippedRecordsAreCountedInTheNotes) {
  ReadInfo info;
  const Mesh mesh = read_bytes("notes.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\ncstype bezier\nf 1 2 3\nfoo\n", &info);
  EXPECT_EQ(mesh.num_faces(), 1u);
  ASSERT_EQ(info.notes.size(), 2u);
  EXPECT_THAT(info.notes[0], ::testing::HasSubstr("ignored 1 line/point records"));
  EXPECT_THAT(info.notes[1], ::testing::HasSubstr("ignored 2 lines with unknown keywords (first: 'cstype' at line 5)"));
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

//! Little-endian bytes of a value, for crafting binary files.
template <class T>
std::string le_bytes(T value) {
  std::string out(sizeof(T), '\0');
  std::memcpy(out.data(), &value, sizeof(T));
  return out;  // the test machines are little-endian; checked below
}

std::string binary_stl(const std::vector<float>& corners, std::uint32_t announced) {
  std::string out(80, ' ');
  out += le_bytes(announced);
  for (std::size_t i = 0; i + 9 <= corners.size(); i += 9) {
    out += std::string(12, '\0');
    for (std::size_t k = 0; k < 9; ++k) out += le_bytes(corners[i + k]);
    out += std::string(2, '\0');
  }
  return out;
}

std::string binary_ply(std::uint32_t num_vertices, const std::vector<double>& coords, std::uint32_t num_faces,
                       const std::vector<int>& indices) {
  std::string out = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(num_vertices) +
                    "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                    std::to_string(num_faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
  for (double c : coords) out += le_bytes(c);
  for (std::size_t i = 0; i + 3 <= indices.size(); i += 3) {
    out += le_bytes(std::uint8_t{3});
    for (int k = 0; k < 3; ++k) out += le_bytes(std::int32_t{indices[i + static_cast<std::size_t>(k)]});
  }
  return out;
}

struct BadFile {
  const char* label;
  std::string name;   // file name (the extension selects the reader)
  std::string bytes;  // content
  bool io_error;      // IoError (true) or InvalidMeshError (false)
  std::string message_part;
};

const std::string kTri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
const std::string kOffTri = "0 0 0\n1 0 0\n0 1 0\n";
const float kNanF = std::numeric_limits<float>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

std::vector<BadFile> bad_files() {
  return {
      {"empty", "empty.obj", "", true, "empty"},
      {"unknown format", "mesh.xyz", "hello\nworld\n", true, "unknown mesh format"},
      {"not an obj", "text.obj", "hello\nworld\n", true, "not an OBJ file"},
      {"no faces obj", "points.obj", kTri, false, "no faces"},
      {"no faces off", "points.off", "OFF\n3 0 0\n" + kOffTri, false, "no faces"},
      {"no faces ply", "points.ply", binary_ply(3, {0, 0, 0, 1, 0, 0, 0, 1, 0}, 0, {}), false, "no faces"},
      {"nan obj", "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", false, "non-finite"},
      {"inf obj", "inf.obj", "v 0 0 0\nv 1 -inf 0\nv 0 1 0\nf 1 2 3\n", false, "non-finite"},
      {"overflow obj", "huge.obj", "v 0 0 0\nv 1 1e999 0\nv 0 1 0\nf 1 2 3\n", false, "non-finite"},
      {"nan off", "nan.off", "OFF\n3 1 0\n0 0 0\n1 0 NaN\n0 1 0\n3 0 1 2\n", false, "non-finite"},
      {"inf ply", "inf.ply", binary_ply(3, {0, 0, 0, 1, 0, 0, 0, kInf, 0}, 1, {0, 1, 2}), false, "non-finite"},
      {"nan stl", "nan.stl", binary_stl({0, 0, 0, 1, 0, 0, 0, kNanF, 0}, 1), false, "non-finite"},
      {"index out of range obj", "range.obj", kTri + "f 1 2 3\nf 1 2 4\n", false,
       "range.obj:5: face index 4 out of range (file has 3 vertices)"},
      {"negative index out of range obj", "negative.obj", kTri + "f -1 -2 -4\n", false, "face index -4 out of range"},
      {"index zero obj", "zero.obj", kTri + "f 0 1 2\n", false, "face index 0 out of range"},
      {"index out of range off", "range.off", "OFF\n3 1 0\n" + kOffTri + "3 0 1 3\n", false,
       "range.off:6: face index 3 out of range"},
      {"negative index off", "negative.off", "OFF\n3 1 0\n" + kOffTri + "3 0 -1 2\n", false,
       "face index -1 out of range"},
      {"index out of range ply", "range.ply", binary_ply(3, {0, 0, 0, 1, 0, 0, 0, 1, 0}, 1, {0, 1, 7}), false,
       "face index 7 out of range"},
      {"two corners obj", "two.obj", kTri + "f 1 2\n", false, "face with 2 corners"},
      {"two corners off", "two.off", "OFF\n3 1 0\n" + kOffTri + "2 0 1\n", false, "has 2 corners"},
      {"two corners ply", "two.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n" + kOffTri + "2 0 1\n",
       false, "has 2 corners"},
      {"two coordinates obj", "short.obj", "v 0 0\n", true, "short.obj:1: expected 3 coordinates after 'v'"},
      {"not a number obj", "word.obj", "v 0 zero 0\n", true, "expected a number after 'v', got 'zero'"},
      {"double sign obj", "sign.obj", "v +-1 0 0\n", true, "expected a number after 'v', got '+-1'"},
      {"bad corner obj", "corner.obj", kTri + "f 1 2 x3\n", true, "expected a vertex index"},
      {"truncated header off", "header.off", "OFF\n3", true, "header"},
      {"bad keyword off", "keyword.off", "MESH\n3 1 0\n", true, "expected an OFF header"},
      {"counts larger than file off", "counts.off", "OFF\n1000000000 1 0\n" + kOffTri, true,
       "announces 1000000000 vertices"},
      {"file ends early off", "early.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n", true, "file ends at face 0 of 1"},
      {"truncated header ply", "header.ply", "ply\nformat ascii 1.0\nelement vertex 3\n", true, "end_header"},
      {"bad type ply", "type.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float80 x\nend_header\n", true,
       "property TYPE NAME"},
      {"count larger than file ply", "count.ply", binary_ply(4000000000u, {0, 0, 0}, 1, {0, 1, 2}), true,
       "declares 4000000000 records"},
      {"truncated body ply", "body.ply", binary_ply(3, {0, 0, 0, 1, 0, 0, 0, 1, 0}, 1, {0, 1, 2}).substr(0, 250), true,
       "truncated"},
      {"count larger than file stl", "count.stl", binary_stl({0, 0, 0, 1, 0, 0, 0, 1, 0}, 1000000000), true,
       "announces 1000000000 triangles"},
      {"short binary stl", "short.stl", "abc", true, "not an STL file"},
      {"truncated ascii stl", "trunc.stl", "solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n", true,
       "expected 'vertex' or 'endloop'"},
  };
}

TEST(ReadMesh, BadFilesGiveTheRightErrorAndMessage) {
  ASSERT_EQ(le_bytes(std::uint16_t{1})[0], 1) << "crafting helpers assume a little-endian machine";
  const auto dir = test::temp_dir();
  for (const BadFile& bad : bad_files()) {
    SCOPED_TRACE(bad.label);
    const auto path = write_file(dir / bad.name, bad.bytes);
    try {
      read_mesh(path);
      ADD_FAILURE() << "no exception";
    } catch (const IoError& e) {
      EXPECT_TRUE(bad.io_error) << "IoError instead of InvalidMeshError: " << e.what();
      EXPECT_THAT(e.what(), ::testing::HasSubstr(bad.message_part));
      EXPECT_THAT(e.what(), ::testing::HasSubstr(bad.name));
    } catch (const InvalidMeshError& e) {
      EXPECT_FALSE(bad.io_error) << "InvalidMeshError instead of IoError: " << e.what();
      EXPECT_THAT(e.what(), ::testing::HasSubstr(bad.message_part));
      EXPECT_THAT(e.what(), ::testing::HasSubstr(bad.name));
    }
  }
}

TEST(ReadMesh, MissingFileAndFolderAreIoErrors) {
  EXPECT_THROW(read_mesh(test::temp_dir() / "absent.obj"), IoError);
  EXPECT_THROW(read_mesh(test::temp_dir()), IoError);
  EXPECT_THROW(read_mesh("/dev/null"), IoError);  // not a regular file
}

TEST(ReadMesh, UnknownExtensionIsDetectedByContent) {
  const auto dir = test::temp_dir();
  const std::pair<const char*, MeshFormat> cases[] = {
      {"formats/cross_ascii.ply", MeshFormat::Ply},   {"formats/part_ascii.stl", MeshFormat::Stl},
      {"formats/knight_binary.stl", MeshFormat::Stl}, {"cross.off", MeshFormat::Off},
      {"spot.obj", MeshFormat::Obj}};
  for (const auto& [file, format] : cases) {
    SCOPED_TRACE(file);
    const auto copy = dir / (std::filesystem::path(file).stem().string() + ".mesh");
    std::filesystem::copy_file(data_path(file), copy, std::filesystem::copy_options::overwrite_existing);
    ReadInfo info;
    const Mesh mesh = read_mesh(copy, &info);
    EXPECT_EQ(info.format, format);
    EXPECT_EQ(mesh.num_faces(), read_mesh(data_path(file)).num_faces());
  }
}

}  // namespace
}  // namespace subfab
