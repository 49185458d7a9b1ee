// SPDX-License-Identifier: GPL-3.0-or-later
// `subfab validate`'s milled-shape measures (informational), as a user sees them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include <fstream>

#include <Eigen/Geometry>

#include "subfab/mesh/read_mesh.h"
#include "subfab/mesh/write_mesh.h"
#include "support/block_test_shapes.h"
#include "support/test_support.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::run_subfab;
using test::slurp;

nlohmann::json json_of(const std::string& output) { return nlohmann::json::parse(output.substr(output.find('{'))); }

TEST(ValidateCli, MilledShapeOfALeaningBarrelHasItsKnownMeasures) {
  // One block under a 10 deg allowance; its lower faces lean 5 deg: the
  // milled shape fills 4 (t + 2 t^2 / 3) under the widest ring (t = tan 5
  // deg) and its bottom corner is t sqrt 2 / sqrt(1 + 2 t^2) from the barrel.
  const fs::path dir = test::temp_dir();
  const fs::path mesh = dir / "barrel.obj";
  write_mesh(test::barrel_solid(1.0, 1.0, 5.0), mesh);
  ASSERT_EQ(run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "out") +
                       " --no-orient --max-overhang 10 --quiet").exit_code, 0);
  const auto v = run_subfab("validate " + quoted(mesh) + " " + quoted(dir / "out") + " --json");
  ASSERT_EQ(v.exit_code, 0) << v.output;
  const auto j = json_of(v.output);
  EXPECT_TRUE(j["passed"].get<bool>());
  const auto& m = j["milled_shapes"];
  ASSERT_EQ(m["blocks"].size(), 1u);
  const auto& b = m["blocks"][0];
  EXPECT_FALSE(b["exact"].get<bool>());
  EXPECT_TRUE(b["error"].is_null());
  const double t = std::tan(5.0 * 3.14159265358979323846 / 180.0);
  const double error = m["hausdorff_error"].get<double>();
  EXPECT_NEAR(b["filled_volume"].get<double>(), 4.0 * (t + 2.0 * t * t / 3.0), 1e-9);
  EXPECT_NEAR(b["deviation"].get<double>(), t * std::sqrt(2.0) / std::sqrt(1.0 + 2.0 * t * t), error + 1e-9);
  EXPECT_NEAR(b["outside_volume"].get<double>(), b["filled_volume"].get<double>(), 1e-9);
  EXPECT_EQ(m["num_collisions"], 0);
  EXPECT_DOUBLE_EQ(m["max_deviation"].get<double>(), b["deviation"].get<double>());
}

TEST(ValidateCli, PrintsMilledShapesOfAMaxOverhangDecomposition) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = test::data_path("joint.off");
  ASSERT_EQ(run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir) + " --max-overhang 15 --quiet").exit_code,
            0);
  const auto text = run_subfab("validate " + quoted(mesh) + " " + quoted(dir) + " --quiet");
  ASSERT_EQ(text.exit_code, 0) << text.output;  // informational: the checks decide the exit code
  EXPECT_NE(text.output.find("milled shapes (informational): 1 of 2 blocks overhang"), std::string::npos)
      << text.output;
  EXPECT_NE(text.output.find("    block 000: filled "), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("  milled shapes: max deviation "), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("all checks passed"), std::string::npos) << text.output;
  // The JSON agrees with decomposition.json: a block that leans is not exact
  // and has filled material; the measures are consistent with each other.
  const auto doc = nlohmann::json::parse(slurp(dir / "decomposition.json"));
  const auto j = json_of(run_subfab("validate " + quoted(mesh) + " " + quoted(dir) + " --json").output);
  const auto& m = j["milled_shapes"];
  ASSERT_EQ(m["blocks"].size(), doc["blocks"].size());
  const double diagonal = doc["input"]["bbox_diagonal"].get<double>();
  const double error = m["hausdorff_error"].get<double>();
  double filled = 0.0;
  for (std::size_t i = 0; i < m["blocks"].size(); ++i) {
    const auto& b = m["blocks"][i];
    const bool leans = doc["blocks"][i]["max_overhang_deg"].get<double>() > 0.1;
    EXPECT_EQ(b["exact"].get<bool>(), !leans) << i;
    if (leans) {
      EXPECT_GT(b["filled_volume"].get<double>(), 0.0) << i;
      EXPECT_GT(b["deviation"].get<double>(), 0.0) << i;
    } else {
      EXPECT_EQ(b["filled_volume"].get<double>(), 0.0) << i;
      EXPECT_EQ(b["deviation"].get<double>(), 0.0) << i;
    }
    EXPECT_NEAR(b["deviation_fraction"].get<double>() * diagonal, b["deviation"].get<double>(), 1e-12);
    EXPECT_LE(b["deviation"].get<double>(), b["deviation_to_block"].get<double>() + 2 * error) << i;
    EXPECT_LE(b["outside_distance"].get<double>(), b["deviation"].get<double>() + 2 * error) << i;
    EXPECT_LE(b["outside_volume"].get<double>(), b["filled_volume"].get<double>() * (1 + 1e-9) + 1e-12) << i;
    filled += b["filled_volume"].get<double>();
  }
  EXPECT_NEAR(m["total_filled_volume"].get<double>(), filled, 1e-12 * (1 + filled));
  EXPECT_FALSE(j["checks"].empty());  // the existing keys are still there
}

// Issue 17: within a tolerance decompose writes its blocks as it holds them
// in its working frame (frame/), and validate measures check 10 there. A
// cube with a spike no axis sees, turned so that decompose turns it back:
// check 10 is measured in the frame and passes; a frame block with a vertex
// moved is refused (check 10 fails, exit 3); a folder without the frame
// blocks (written before them) is measured the old way and passes.
TEST(ValidateCli, MeasuresCheckTenInDecomposesFrameAndRefusesATamperedFrameBlock) {
  const fs::path dir = test::temp_dir();
  Mesh spike = read_mesh(test::data_path("regression/cube_tiny_diagonal_spike.obj"));
  transform_mesh(spike, Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix(), Vec3::Zero());
  const fs::path mesh = dir / "turned_spike.obj";
  write_mesh(spike, mesh);
  const fs::path out = dir / "out";
  const auto d = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(out) + " --tolerance 5e-4 --no-view --quiet");
  ASSERT_EQ(d.exit_code, 0) << d.output;
  auto doc = nlohmann::ordered_json::parse(slurp(out / "decomposition.json"));
  ASSERT_TRUE(doc.contains("frame"));
  ASSERT_NE(doc["rotation"][0][0].get<double>(), 1.0);  // turned
  ASSERT_FALSE(doc["blocks"].empty());
  const std::string frame_block = doc["blocks"][0]["frame_mesh"].get<std::string>();
  EXPECT_EQ(frame_block, "frame/block_000.obj");
  ASSERT_TRUE(fs::exists(out / frame_block));
  EXPECT_LT(doc["frame"]["max_rounding"].get<double>(), 1e-9 * doc["input"]["bbox_diagonal"].get<double>());

  const auto v = run_subfab("validate " + quoted(mesh) + " " + quoted(out) + " --json --quiet");
  ASSERT_EQ(v.exit_code, 0) << v.output;
  const auto j = json_of(v.output);
  EXPECT_TRUE(j["deviation"]["measured_in_frame"].get<bool>());
  EXPECT_GE(j["deviation"]["error_bound"].get<double>(), j["deviation"]["frame_rounding"].get<double>());
  ASSERT_EQ(j["checks"].size(), 10u);

  // A vertex of the frame block moved by 1e-3 x diagonal: refused.
  const Mesh good = read_mesh(out / frame_block);
  Mesh moved = good;
  moved.vertices[0].z() += 1e-3 * doc["input"]["bbox_diagonal"].get<double>();
  write_mesh(moved, out / frame_block);
  const auto t = run_subfab("validate " + quoted(mesh) + " " + quoted(out) + " --quiet");
  EXPECT_EQ(t.exit_code, 3) << t.output;
  EXPECT_NE(t.output.find("block 000: frame block refused (frame/ does not match blocks/): vertex 0"),
            std::string::npos) << t.output;
  write_mesh(good, out / frame_block);

  // Without the frame blocks (an older folder): the exported blocks are measured.
  doc.erase("frame");
  for (auto& b : doc["blocks"]) b.erase("frame_mesh");
  std::ofstream(out / "decomposition.json") << doc.dump(2) << "\n";
  fs::remove_all(out / "frame");
  const auto old = run_subfab("validate " + quoted(mesh) + " " + quoted(out) + " --json --quiet");
  ASSERT_EQ(old.exit_code, 0) << old.output;
  EXPECT_FALSE(json_of(old.output)["deviation"]["measured_in_frame"].get<bool>());
}

TEST(ValidateCli, AnExactDecompositionSaysItsMilledShapesAreItsBlocks) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = test::data_path("joint.off");
  ASSERT_EQ(run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir) + " --quiet").exit_code, 0);
  const auto v = run_subfab("validate " + quoted(mesh) + " " + quoted(dir) + " --quiet");
  ASSERT_EQ(v.exit_code, 0) << v.output;
  EXPECT_NE(v.output.find("every block is an exact height field, its milled shape is the block"), std::string::npos)
      << v.output;
  const auto j = json_of(run_subfab("validate " + quoted(mesh) + " " + quoted(dir) + " --json").output);
  EXPECT_EQ(j["milled_shapes"]["num_exact"], j["num_blocks"]);
  EXPECT_EQ(j["milled_shapes"]["max_deviation"], 0.0);
}

TEST(ValidateCli, ReportsEveryBlocksThicknessAndTheNewChecks) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = test::data_path("joint.off");
  ASSERT_EQ(run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir) + " --quiet").exit_code, 0);
  const auto doc = nlohmann::json::parse(slurp(dir / "decomposition.json"));
  const auto j = json_of(run_subfab("validate " + quoted(mesh) + " " + quoted(dir) + " --json").output);
  ASSERT_TRUE(j["passed"].get<bool>());
  ASSERT_EQ(j["checks"].size(), 9u);  // 7 + single precision + slivers (10 with a tolerance)
  EXPECT_EQ(j["checks"][7]["name"], "machine meshes closed solids in single precision");
  EXPECT_EQ(j["checks"][8]["name"].get<std::string>().rfind("no slivers", 0), 0u);
  const auto& t = j["thickness"];
  ASSERT_EQ(t["blocks"].size(), doc["blocks"].size());
  EXPECT_EQ(t["num_slivers"], 0);
  double thinnest = 1e300;
  for (std::size_t i = 0; i < doc["blocks"].size(); ++i) {
    // decompose records the same thickness as validate measures (same mesh, same frame).
    EXPECT_NEAR(t["blocks"][i]["thickness"].get<double>(), doc["blocks"][i]["thickness"].get<double>(),
                1e-12 * doc["input"]["bbox_diagonal"].get<double>())
        << i;
    EXPECT_GT(doc["blocks"][i]["thickness"].get<double>(), 0.0) << i;
    thinnest = std::min(thinnest, doc["blocks"][i]["thickness"].get<double>());
  }
  EXPECT_DOUBLE_EQ(doc["summary"]["min_thickness"].get<double>(), thinnest);
  EXPECT_NEAR(t["min_thickness"].get<double>(), thinnest, 1e-12 * doc["input"]["bbox_diagonal"].get<double>());
  const auto text = run_subfab("validate " + quoted(mesh) + " " + quoted(dir) + " --quiet");
  EXPECT_NE(text.output.find("  thinnest block: block "), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("  9. PASS  no slivers"), std::string::npos) << text.output;
}

}  // namespace
}  // namespace subfab
