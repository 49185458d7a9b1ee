// SPDX-License-Identifier: GPL-3.0-or-later
// `subfab repair`, `decompose --repair`, `unfold --repair` on the crafted
// bad-input corpus: exit 0 with a valid solid, or exit 2 with the reason;
// refusals without --repair name it; the repair is recorded in the outputs
// and validate checks the repaired solid.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "subfab/checks/analyze_mesh.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::run_subfab;

fs::path bad(const std::string& name) { return test::data_path("regression/bad_inputs/" + name); }

TEST(RepairCli, EveryCorpusFileIsRepairedOrRefusedWithTheReason) {
  const fs::path dir = test::temp_dir();
  struct Case {
    const char* file;
    int exit_code;
    const char* says;  // in the output
  };
  const Case cases[] = {
      {"cube_flipped_face.obj", 0, "orient"},
      {"cube_duplicated_face.obj", 0, "duplicate_faces"},
      {"cube_zero_area_sliver.obj", 0, "zero_area_faces"},
      {"sphere_inward.obj", 0, "orient_outward"},
      {"two_cubes_touching_at_vertex.obj", 0, "separate_pinches"},
      {"two_overlapping_cubes.obj", 2, "raise --max-deviation"},
      {"cube_hole.obj", 2, "raise --max-deviation"},
      {"open_triangle.obj", 2, "encloses no volume"},
      {"empty.obj", 2, "empty"},
      {"random_bytes.stl", 2, "truncated"},
      {"nan_coordinates.obj", 2, "non-finite"},
  };
  for (const Case& c : cases) {
    const fs::path out = dir / (std::string(c.file) + ".repaired.obj");
    const auto r = run_subfab("repair " + quoted(bad(c.file)) + " -o " + quoted(out));
    EXPECT_EQ(r.exit_code, c.exit_code) << c.file << "\n" << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.file << "\n" << r.output;
    if (c.exit_code == 0) {
      ASSERT_TRUE(fs::exists(out)) << c.file;
      EXPECT_TRUE(analyze_mesh(read_mesh(out)).all_passed()) << c.file;
    } else {
      EXPECT_FALSE(fs::exists(out)) << c.file;
      EXPECT_NE(r.output.find("error: "), std::string::npos) << c.file;
    }
  }
  // A larger cap lets the union and the filled hole through.
  for (const char* file : {"two_overlapping_cubes.obj", "cube_hole.obj"}) {
    const fs::path out = dir / (std::string(file) + ".capped.obj");
    const auto r = run_subfab("repair " + quoted(bad(file)) + " -o " + quoted(out) + " --max-deviation 0.5 --json");
    ASSERT_EQ(r.exit_code, 0) << file << "\n" << r.output;
    const auto j = nlohmann::json::parse(r.output.substr(r.output.find('{')));
    EXPECT_TRUE(j.at("changed").get<bool>());
    EXPECT_GT(j.at("steps").size(), 0u);
    EXPECT_LE(j.at("max_deviation_fraction").get<double>(), 0.5);
    EXPECT_TRUE(analyze_mesh(read_mesh(out)).all_passed()) << file;
  }
}

TEST(RepairCli, IsDeterministic) {
  // Two runs of the command give the same file (within one process the
  // second local remeshing can differ: see docs/repair.md, limits).
  const fs::path dir = test::temp_dir();
  for (const char* out : {"a.obj", "b.obj"})
    ASSERT_EQ(run_subfab("repair " + quoted(bad("two_overlapping_cubes.obj")) + " -o " + quoted(dir / out) +
                         " --max-deviation 0.5 -q")
                  .exit_code,
              0);
  EXPECT_EQ(test::slurp(dir / "a.obj"), test::slurp(dir / "b.obj"));
}

TEST(RepairCli, RefusalWithoutRepairNamesIt) {
  const fs::path dir = test::temp_dir();
  for (const char* command : {"decompose", "unfold"}) {
    const auto r = run_subfab(std::string(command) + " " + quoted(bad("cube_flipped_face.obj")) + " -o " +
                              quoted(dir / command));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--repair"), std::string::npos) << r.output;
  }
}

TEST(RepairCli, DecomposeRepairRecordsItAndValidateUsesTheRepairedSolid) {
  const fs::path dir = test::temp_dir();
  const fs::path input = bad("two_cubes_touching_at_vertex.obj");
  const auto d = run_subfab("decompose " + quoted(input) + " -o " + quoted(dir) + " --repair --json");
  ASSERT_EQ(d.exit_code, 0) << d.output;
  EXPECT_NE(d.output.find("REPAIRED INPUT"), std::string::npos) << d.output;
  ASSERT_TRUE(fs::exists(dir / "input_mesh_repaired.obj"));
  const auto doc = nlohmann::json::parse(test::slurp(dir / "decomposition.json"));
  const auto& in = doc.at("input");
  EXPECT_EQ(in.at("decomposed_mesh"), "input_mesh_repaired.obj");
  EXPECT_EQ(in.at("mesh_repair").at("mesh"), "input_mesh_repaired.obj");
  EXPECT_NE(in.at("mesh_repair").at("applied_steps").get<std::string>().find("separate_pinches"),
            std::string::npos);
  const auto v = run_subfab("validate " + quoted(input) + " " + quoted(dir));
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_NE(v.output.find("REPAIRED input"), std::string::npos) << v.output;
  EXPECT_NE(v.output.find("--repair"), std::string::npos) << v.output;

  // Without --repair on a valid input, the stale repaired solid goes and the
  // input itself is what is decomposed.
  const fs::path cube = dir / "cube.obj";
  ASSERT_EQ(run_subfab("repair " + quoted(bad("cube_flipped_face.obj")) + " -o " + quoted(cube) + " -q").exit_code, 0);
  ASSERT_EQ(run_subfab("decompose " + quoted(cube) + " -o " + quoted(dir) + " -q").exit_code, 0);
  EXPECT_FALSE(fs::exists(dir / "input_mesh_repaired.obj"));
  const auto again = nlohmann::json::parse(test::slurp(dir / "decomposition.json"));
  EXPECT_TRUE(again.at("input").at("mesh_repair").is_null());
  EXPECT_EQ(again.at("input").at("decomposed_mesh"), cube.string());
}

TEST(RepairCli, UnfoldRepairRecordsIt) {
  const fs::path dir = test::temp_dir();
  const auto u = run_subfab("unfold " + quoted(bad("sphere_inward.obj")) + " -o " + quoted(dir) + " --repair -q");
  ASSERT_EQ(u.exit_code, 0) << u.output;
  const auto doc = nlohmann::json::parse(test::slurp(dir / "unfold.json"));
  EXPECT_EQ(doc.at("input").at("unfolded_mesh"), "input_mesh_repaired.obj");
  EXPECT_EQ(doc.at("input").at("mesh_repair").at("applied_steps"), "orient_outward");
  EXPECT_TRUE(fs::exists(dir / "input_mesh_repaired.obj"));
}

}  // namespace
}  // namespace subfab
