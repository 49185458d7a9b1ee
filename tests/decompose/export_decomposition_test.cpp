// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/export_decomposition.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/block_test_shapes.h"
#include "subfab/decompose/carve_blocks.h"
#include "subfab/validate/validate_decomposition.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;

using test::slurp;

//! An L in a rotated frame, carved by two boxes of the canonical frame.
struct Fixture {
  Mesh input;
  DecomposeResult result;
  Fixture() {
    const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    input = test::l_solid();
    transform_mesh(input, rotation.transpose(), Vec3::Zero());
    result.rotation = rotation;
    result.canonical = input;
    transform_mesh(result.canonical, rotation, Vec3::Zero());
    result.num_input_vertices = input.num_vertices();
    const std::vector<HeightBox> boxes = {test::make_height_box({-1, -1, -1}, {3, 0.5, 2}, Axis::PosZ),
                                          test::make_height_box({-1, -1, -1}, {3, 3, 2}, Axis::PosY)};
    result.blocks = carve_blocks(result.canonical, boxes).blocks;
    result.timings.total = 1.25;
  }
};

TEST(ExportDecomposition, AxisToMachineIsARotationTakingTheAxisToZ) {
  for (Axis a : kAllAxes) {
    const Eigen::Matrix3d q = axis_to_machine(a);
    EXPECT_NEAR(q.determinant(), 1.0, 0.0);
    EXPECT_TRUE((q * q.transpose()).isIdentity(0.0));
    EXPECT_EQ(q * axis_direction(a), Vec3::UnitZ());
  }
}

TEST(ExportDecomposition, WritesTheDocumentedFilesAndTheyValidate) {
  const Fixture f;
  ASSERT_EQ(f.result.blocks.size(), 2u);
  const fs::path dir = test::temp_dir();
  ExportInfo info;
  info.input_path = "l.obj";
  info.options.max_height_fraction = 0.9;
  export_decomposition(f.input, f.result, info, dir);
  const nlohmann::json doc = nlohmann::json::parse(slurp(dir / "decomposition.json"));
  EXPECT_EQ(doc["format"], "subfab.decomposition");
  EXPECT_EQ(doc["version"], 1);
  EXPECT_EQ(doc["input"]["vertices"], f.input.num_vertices());
  EXPECT_EQ(doc["input"]["faces"], f.input.num_faces());
  EXPECT_EQ(doc["rotation"].size(), 3u);
  EXPECT_EQ(doc["parameters"]["max_height_fraction"], 0.9);
  EXPECT_TRUE(doc["parameters"]["machine"].is_null());
  ASSERT_EQ(doc["blocks"].size(), 2u);
  for (const char* key : {"orient", "field", "grow", "cover", "resolve", "carve", "total"})
    EXPECT_TRUE(doc["timings_s"].contains(key)) << key;
  EXPECT_EQ(doc["summary"]["num_blocks"], 2);
  EXPECT_NEAR(doc["summary"]["material_volume_fraction"].get<double>(), 1.0, 1e-9);
  const auto& b0 = doc["blocks"][0];
  EXPECT_EQ(b0["mesh"], "blocks/block_000.obj");
  EXPECT_EQ(b0["machine_mesh"], "mill/block_000.stl");
  EXPECT_EQ(b0["axis"], "+z");
  const Vec3 d0(b0["direction"][0].get<double>(), b0["direction"][1].get<double>(), b0["direction"][2].get<double>());
  EXPECT_NEAR((d0 - f.result.rotation.transpose() * Vec3::UnitZ()).norm(), 0.0, 1e-15);
  EXPECT_NEAR(b0["volume"].get<double>(), 1.0, 1e-9);  // the strip y < 0.5 of the L
  EXPECT_NEAR(b0["height"].get<double>(), 1.0, 1e-9);

  // Read everything back and validate it.
  std::vector<ValidationBlock> blocks;
  for (const auto& b : doc["blocks"]) {
    ValidationBlock vb;
    vb.mesh = read_mesh(dir / b["mesh"].get<std::string>());
    vb.machine_mesh = read_mesh(dir / b["machine_mesh"].get<std::string>());
    vb.direction = Vec3(b["direction"][0].get<double>(), b["direction"][1].get<double>(), b["direction"][2].get<double>());
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) vb.machine_transform(r, c) = b["machine_transform"][r][c].get<double>();
    EXPECT_NEAR(bounding_box(*vb.machine_mesh).min.z(), 0.0, 1e-12);
    blocks.push_back(vb);
  }
  // Vertices that are input vertices keep the input's exact coordinates.
  std::size_t exact = 0;
  for (const Vec3& v : blocks[0].mesh.vertices)
    for (const Vec3& w : f.input.vertices) exact += (v == w) ? 1 : 0;
  EXPECT_GE(exact, 4u);
  const ValidationReport report = validate_decomposition(f.input, blocks);
  for (const CheckReport& c : report.checks)
    EXPECT_TRUE(c.passed) << c.name << ": " << (c.failures.empty() ? c.summary : c.failures[0]);
}

TEST(ExportDecomposition, OutputIsByteIdenticalApartFromTimings) {
  Fixture f;
  const fs::path dir = test::temp_dir();
  ExportInfo info;
  info.input_path = "l.obj";
  export_decomposition(f.input, f.result, info, dir / "a");
  f.result.timings.total = 99.0;
  f.result.timings.carve = 3.0;
  export_decomposition(f.input, f.result, info, dir / "b");
  for (const char* file : {"blocks/block_000.obj", "blocks/block_001.obj", "mill/block_000.stl", "mill/block_001.stl"})
    EXPECT_EQ(slurp(dir / "a" / file), slurp(dir / "b" / file)) << file;
  nlohmann::json a = nlohmann::json::parse(slurp(dir / "a" / "decomposition.json"));
  nlohmann::json b = nlohmann::json::parse(slurp(dir / "b" / "decomposition.json"));
  EXPECT_NE(a["timings_s"], b["timings_s"]);
  a.erase("timings_s");
  b.erase("timings_s");
  EXPECT_EQ(a.dump(), b.dump());
}

}  // namespace
}  // namespace subfab
