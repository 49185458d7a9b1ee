// SPDX-License-Identifier: GPL-3.0-or-later
// STL reading (src/mesh/read_stl.cpp) on the samples of data/formats/.
#include <gtest/gtest.h>

#include "support/mesh_compare.h"
#include "subfab/core/error.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

using test::data_path;

std::filesystem::path sample(const std::string& name) { return data_path("formats") / name; }

//! The STL sample holds the same oriented triangles as the source model
//! (coordinates rounded to float32 for binary STL) and welding recovered
//! exactly the source's shared vertices.
void expect_same_as_source(const std::string& stl, const std::string& source_name, bool float32) {
  SCOPED_TRACE(stl);
  const Mesh source = read_mesh(data_path(source_name));
  ReadInfo info;
  const Mesh mesh = read_mesh(sample(stl), &info);
  EXPECT_EQ(info.format, MeshFormat::Stl);
  EXPECT_EQ(mesh.num_faces(), source.num_faces());
  EXPECT_EQ(mesh.num_vertices(), source.num_vertices());
  EXPECT_EQ(info.vertices_in_file, 3 * source.num_faces());
  EXPECT_EQ(info.vertices_welded, 3 * source.num_faces() - source.num_vertices());
  EXPECT_EQ(test::sorted_corner_triangles(mesh, false), test::sorted_corner_triangles(source, float32));
}

TEST(ReadStl, AsciiFullPrecision) { expect_same_as_source("part_ascii.stl", "part.off", false); }

TEST(ReadStl, Binary) { expect_same_as_source("knight_binary.stl", "decimated_knight.off", true); }

TEST(ReadStl, BinaryWhoseHeaderStartsWithSolid) {
  expect_same_as_source("cross_binary_solid.stl", "cross.off", true);
}

TEST(ReadStl, HandWrittenTwoSolidsUppercaseAndFacetWithoutNormal) {
  ReadInfo info;
  const Mesh mesh = read_mesh(sample("tetra_two_solids.stl"), &info);
  EXPECT_EQ(mesh.num_faces(), 4u);
  EXPECT_EQ(mesh.num_vertices(), 4u);
  EXPECT_EQ(info.vertices_welded, 8u);
  EXPECT_DOUBLE_EQ(signed_volume(mesh), 1.0 / 6.0);
}

}  // namespace
}  // namespace subfab
