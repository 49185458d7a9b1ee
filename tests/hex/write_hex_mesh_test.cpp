// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/write_hex_mesh.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include "support/hex_test_shapes.h"

namespace subfab {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

HexMesh unit_cube() { return test::unit_hex_cube(); }

TEST(WriteHexMesh, MeditHasOneBasedHexahedra) {
  const auto dir = std::filesystem::path(SUBFAB_TEST_TMP_DIR) / "write_hex_mesh";
  std::filesystem::create_directories(dir);
  write_medit_hex_mesh(unit_cube(), dir / "c.mesh");
  const std::string text = slurp(dir / "c.mesh");
  EXPECT_NE(text.find("Vertices\n8\n"), std::string::npos);
  EXPECT_NE(text.find("Hexahedra\n1\n1 2 3 4 5 6 7 8 0\n"), std::string::npos);
  EXPECT_NE(text.find("End"), std::string::npos);
}

TEST(WriteHexMesh, VtkHasCellType12AndTheCellData) {
  const auto dir = std::filesystem::path(SUBFAB_TEST_TMP_DIR) / "write_hex_mesh";
  std::filesystem::create_directories(dir);
  write_vtk_hex_mesh(unit_cube(), dir / "c.vtk", {0.75});
  const std::string text = slurp(dir / "c.vtk");
  EXPECT_NE(text.find("DATASET UNSTRUCTURED_GRID"), std::string::npos);
  EXPECT_NE(text.find("CELLS 1 9\n8 0 1 2 3 4 5 6 7\n"), std::string::npos);
  EXPECT_NE(text.find("CELL_TYPES 1\n12\n"), std::string::npos);
  EXPECT_NE(text.find("SCALARS scaled_jacobian double 1\nLOOKUP_TABLE default\n0.75\n"), std::string::npos);
}

TEST(WriteHexMesh, UnwritablePathThrows) {
  EXPECT_THROW(write_medit_hex_mesh(unit_cube(), "/nonexistent-folder/x.mesh"), std::exception);
}

}  // namespace
}  // namespace subfab
