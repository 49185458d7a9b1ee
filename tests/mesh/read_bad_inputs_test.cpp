// SPDX-License-Identifier: GPL-3.0-or-later
// The reading part of the crafted bad-input corpus (data/regression/bad_inputs,
// issue 13): the files no repair can use are refused by the reader with a
// subfab::IoError / InvalidMeshError naming the problem; the others read as
// meshes with indices in range. Runs under ASan/UBSan too (CGAL-free).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "subfab/core/error.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

std::filesystem::path bad(const std::string& name) {
  return test::data_path("regression/bad_inputs/" + name);
}

std::string read_error(const std::string& name) {
  try {
    read_mesh(bad(name));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ReadBadInputs, UnusableFilesAreRefusedWithTheReason) {
  EXPECT_NE(read_error("empty.obj").find("empty"), std::string::npos) << read_error("empty.obj");
  EXPECT_NE(read_error("random_bytes.stl").find("truncated"), std::string::npos) << read_error("random_bytes.stl");
  EXPECT_NE(read_error("nan_coordinates.obj").find("non-finite"), std::string::npos)
      << read_error("nan_coordinates.obj");
}

TEST(ReadBadInputs, RepairableFilesReadAsMeshes) {
  for (const char* name : {"cube_flipped_face.obj", "two_overlapping_cubes.obj", "cube_hole.obj",
                           "cube_duplicated_face.obj", "cube_zero_area_sliver.obj",
                           "two_cubes_touching_at_vertex.obj", "sphere_inward.obj", "open_triangle.obj"}) {
    const Mesh m = read_mesh(bad(name));
    EXPECT_FALSE(m.faces.empty()) << name;
    for (const auto& t : m.faces)
      for (int v : t) EXPECT_TRUE(v >= 0 && static_cast<std::size_t>(v) < m.num_vertices()) << name;
    for (const auto& p : m.vertices) EXPECT_TRUE(p.allFinite()) << name;
  }
}

}  // namespace
}  // namespace subfab
