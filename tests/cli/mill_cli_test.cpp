// SPDX-License-Identifier: GPL-3.0-or-later
// `subfab mill` as a user runs it, on a decomposition of data/joint.off.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "support/rs274_words.h"
#include "support/test_support.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::run_subfab;
using test::slurp;

//! joint.off decomposed once per test into `dir` (two blocks).
void decompose_joint(const fs::path& dir) {
  auto r = run_subfab("decompose " + quoted(test::data_path("joint.off")) + " -o " + quoted(dir) + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
}

TEST(MillCli, WritesCheckedGcodeAndTheSameBytesWhateverThreads) {
  const fs::path dir = test::temp_dir();
  decompose_joint(dir);
  auto one = run_subfab("mill " + quoted(dir) + " --size 60 --threads 1 -o " + quoted(dir / "g1"));
  ASSERT_EQ(one.exit_code, 0) << one.output;
  EXPECT_NE(one.output.find("max gouge"), std::string::npos) << one.output;
  auto two = run_subfab("mill " + quoted(dir) + " --size 60 --threads 2 --quiet");  // default folder OUTDIR/gcode
  ASSERT_EQ(two.exit_code, 0) << two.output;
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir / "g1")) {
    const fs::path name = entry.path().filename();
    EXPECT_EQ(slurp(entry.path()), slurp(dir / "gcode" / name)) << name;
    ++files;
  }
  EXPECT_EQ(files, 5u);  // two blocks, their pictures and mill.json

  const auto doc = nlohmann::json::parse(slurp(dir / "g1" / "mill.json"));
  EXPECT_EQ(doc["format"], "subfab.mill");
  EXPECT_EQ(doc["units"], "mm");
  EXPECT_GT(doc["scale_mm_per_unit"].get<double>(), 0.0);
  ASSERT_EQ(doc["blocks"].size(), 2u);
  for (const auto& b : doc["blocks"]) {
    for (const char* key : {"id", "gcode", "axis", "stock_mm", "time_s", "max_gouge_mm", "max_residual_mm",
                            "mean_residual_mm", "unreachable_area_mm2", "foot_area_mm2", "picture", "passed"})
      EXPECT_TRUE(b.contains(key)) << key;
    EXPECT_LE(b["max_gouge_mm"].get<double>(), doc["parameters"]["resolution_mm"].get<double>());
    EXPECT_GT(b["time_s"].get<double>(), 0.0);
    const auto stock = b["stock_mm"];
    // The largest stock side is at most the model's 60 mm plus two margins.
    EXPECT_LE(std::max({stock[0].get<double>(), stock[1].get<double>(), stock[2].get<double>()}), 70.0 + 1e-9);
    const std::string gcode = slurp(dir / "g1" / b["gcode"].get<std::string>());
    const auto words = test::check_rs274(gcode, {stock[0].get<double>() + 0.001, stock[1].get<double>() + 0.001, 1e9});
    EXPECT_TRUE(words.problems.empty()) << words.problems.front();
    EXPECT_EQ(words.last_code, "M30");
    std::ifstream png(dir / "g1" / b["picture"].get<std::string>(), std::ios::binary);
    char signature[4] = {};
    png.read(signature, 4);
    EXPECT_TRUE(png && signature[1] == 'P' && signature[2] == 'N' && signature[3] == 'G');
  }
  EXPECT_TRUE(doc["summary"]["passed"].get<bool>());
}

TEST(MillCli, LinuxCncDialectScaleAndJson) {
  const fs::path dir = test::temp_dir();
  decompose_joint(dir);
  auto r = run_subfab("mill " + quoted(dir) + " --scale 0.5 --dialect linuxcnc --tool ball:4 --rough-tool none "
                      "--stepover 0.2 --resolution 0.3 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto doc = nlohmann::json::parse(r.output.substr(r.output.find('{')));
  EXPECT_DOUBLE_EQ(doc["scale_mm_per_unit"].get<double>(), 0.5);
  EXPECT_TRUE(doc["roughing_tool"].is_null());
  EXPECT_EQ(doc["finishing_tool"], "ball:4");
  const std::string gcode = slurp(dir / "gcode" / "block_000.nc");
  const auto words = test::check_rs274(gcode, {});
  EXPECT_TRUE(words.problems.empty()) << words.problems.front();
  EXPECT_TRUE(words.percent_wrapped);
  EXPECT_EQ(words.last_code, "M2");
  EXPECT_EQ(words.num_pauses, 0);  // one tool: no tool change
}

TEST(MillCli, RefusesBadArguments) {
  const fs::path dir = test::temp_dir();
  decompose_joint(dir);
  EXPECT_EQ(run_subfab("mill " + quoted(dir)).exit_code, 1);                          // no --size nor --scale
  EXPECT_EQ(run_subfab("mill " + quoted(dir) + " --size 50 --scale 2").exit_code, 1);  // both
  EXPECT_EQ(run_subfab("mill " + quoted(dir) + " --size 50 --tool cone:3").exit_code, 1);
  EXPECT_EQ(run_subfab("mill " + quoted(dir) + " --size 50 --tool ball:-3").exit_code, 1);
  EXPECT_EQ(run_subfab("mill " + quoted(dir) + " --size 50 --rough-tool ball:8").exit_code, 1);
  EXPECT_EQ(run_subfab("mill " + quoted(dir) + " --size 50 --dialect fanuc").exit_code, 1);
  EXPECT_EQ(run_subfab("mill " + quoted(dir) + " --size -5").exit_code, 1);
  auto missing = run_subfab("mill " + quoted(dir / "nope") + " --size 50");
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("decomposition.json"), std::string::npos) << missing.output;
  std::ofstream(dir / "decomposition.json") << "{\"format\": \"subfab.decomposition\"}";
  EXPECT_EQ(run_subfab("mill " + quoted(dir) + " --size 50").exit_code, 2);
}

}  // namespace
}  // namespace subfab
