// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mesh/write_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "subfab/core/error.h"
#include "support/mesh_compare.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

//! A mesh whose coordinates need all 17 digits (and a negative zero, a
//! denormal and a huge value) to test exactness of the text writers.
Mesh awkward_mesh() {
  const Mesh knight = read_mesh(test::data_path("decimated_knight.off"));
  Mesh mesh = knight;
  mesh.vertices[0] = Vec3(0.1 + 0.2, -1.0 / 3.0, 1e-310);
  mesh.vertices[1] = Vec3(-0.0, 123456789.123456789, 1.7976931348623157e308 / 4);
  mesh.vertices[2] = Vec3(std::nextafter(1.0, 2.0), std::nextafter(1.0, 0.0), 5e-324);
  return mesh;
}

void expect_same_mesh(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.num_faces(), b.num_faces());
  EXPECT_EQ(a.faces, b.faces);
  for (std::size_t v = 0; v < a.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k)  // bitwise equal, including the sign of zero
      ASSERT_EQ(std::signbit(a.vertices[v][k]), std::signbit(b.vertices[v][k])) << v;
  EXPECT_EQ(a.vertices, b.vertices);
}

TEST(WriteMesh, ObjRoundTripIsExact) {
  const Mesh mesh = awkward_mesh();
  const auto path = test::temp_dir() / "out.obj";
  write_mesh(mesh, path);
  expect_same_mesh(mesh, read_mesh(path));
}

TEST(WriteMesh, OffRoundTripIsExact) {
  const Mesh mesh = awkward_mesh();
  const auto path = test::temp_dir() / "out.OFF";  // extension case does not matter
  write_mesh(mesh, path);
  expect_same_mesh(mesh, read_mesh(path));
}

TEST(WriteMesh, PlyRoundTripIsExact) {
  const Mesh mesh = awkward_mesh();
  const auto path = test::temp_dir() / "out.ply";
  write_mesh(mesh, path);
  ReadInfo info;
  expect_same_mesh(mesh, read_mesh(path, &info));
  EXPECT_EQ(info.format, MeshFormat::Ply);
}

TEST(WriteMesh, StlRoundTripIsFloat32Exact) {
  for (const char* name : {"decimated_knight.off", "fandisk.obj", "spot.obj"}) {
    SCOPED_TRACE(name);
    const Mesh mesh = read_mesh(test::data_path(name));
    const auto path = test::temp_dir() / "out.stl";
    write_mesh(mesh, path);
    EXPECT_EQ(std::filesystem::file_size(path), 84 + 50 * mesh.num_faces());
    ReadInfo info;
    const Mesh back = read_mesh(path, &info);
    EXPECT_EQ(back.num_faces(), mesh.num_faces());
    EXPECT_EQ(back.num_vertices(), mesh.num_vertices());  // welding restores the shared vertices
    EXPECT_EQ(test::sorted_corner_triangles(back, false), test::sorted_corner_triangles(mesh, true));
  }
}

TEST(WriteMesh, EveryWriterRoundTripsADataModel) {
  const Mesh mesh = read_mesh(test::data_path("fandisk.obj"));
  for (const char* ext : {".obj", ".off", ".ply"}) {
    SCOPED_TRACE(ext);
    const auto path = test::temp_dir() / (std::string("fandisk") + ext);
    write_mesh(mesh, path);
    expect_same_mesh(mesh, read_mesh(path));
  }
}

TEST(WriteMesh, UnknownExtensionIsAnIoError) {
  const Mesh mesh = read_mesh(test::data_path("cross.off"));
  EXPECT_THROW(write_mesh(mesh, test::temp_dir() / "out.xyz"), IoError);
}

TEST(WriteMesh, UnwritablePathIsAnIoError) {
  const Mesh mesh = read_mesh(test::data_path("cross.off"));
  EXPECT_THROW(write_mesh(mesh, test::temp_dir() / "no_such_folder" / "out.obj"), IoError);
}

TEST(WriteMesh, OutOfRangeFaceIsRefused) {
  Mesh mesh = read_mesh(test::data_path("cross.off"));
  mesh.faces[3][1] = static_cast<int>(mesh.num_vertices());
  EXPECT_THROW(write_mesh(mesh, test::temp_dir() / "out.stl"), InvalidMeshError);
}

TEST(WriteMesh, NonFiniteOrTooLargeForStlIsRefused) {
  Mesh mesh = read_mesh(test::data_path("cross.off"));
  const auto dir = test::temp_dir();
  mesh.vertices[5].y() = 1e300;  // fine in double formats, not in float32 STL
  EXPECT_NO_THROW(write_mesh(mesh, dir / "big.ply"));
  EXPECT_THROW(write_mesh(mesh, dir / "big.stl"), InvalidMeshError);
  mesh.vertices[5].y() = std::numeric_limits<double>::quiet_NaN();
  for (const char* name : {"nan.obj", "nan.off", "nan.ply", "nan.stl"}) {
    EXPECT_THROW(write_mesh(mesh, dir / name), InvalidMeshError) << name;
    EXPECT_FALSE(std::filesystem::exists(dir / name)) << name;
  }
}

}  // namespace
}  // namespace subfab
