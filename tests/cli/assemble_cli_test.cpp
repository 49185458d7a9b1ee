// SPDX-License-Identifier: GPL-3.0-or-later
// The browser pages as a user gets them: written by decompose and unfold
// (or not, with --no-view), `subfab assemble`, and their errors.
#include <gtest/gtest.h>

#include <cstdlib>

#include <nlohmann/json.hpp>

#include "subfab/view/plan_gluing_order.h"
#include "subfab/view/read_decomposition.h"
#include "support/test_support.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::run_subfab;

TEST(AssembleCli, DecomposeWritesThePagesAndAssembleRewritesTheSheet) {
  const fs::path dir = test::temp_dir();
  const std::string mesh = quoted(test::data_path("joint.off"));
  ASSERT_EQ(run_subfab("decompose " + mesh + " -o " + quoted(dir / "a") + " --quiet").exit_code, 0);
  if (!std::getenv("SUBFAB_THREE_JS") && !fs::exists("/usr/share/javascript/three/three.min.js"))
    GTEST_SKIP() << "libjs-three not installed";
  EXPECT_TRUE(fs::exists(dir / "a" / "view.html"));
  EXPECT_TRUE(fs::exists(dir / "a" / "assembly.html"));
  EXPECT_EQ(test::slurp(dir / "a" / "assembly.html").find(" mm "), std::string::npos);  // model units

  auto r = run_subfab("assemble " + quoted(dir / "a") + " --size 100 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output.substr(r.output.find('{')));
  EXPECT_EQ(j["steps"].size(), 2u);  // joint.off: two blocks
  EXPECT_TRUE(j["stuck"].empty());
  EXPECT_GT(j["mm_per_unit"].get<double>(), 0);
  EXPECT_NE(test::slurp(dir / "a" / "assembly.html").find(" mm<"), std::string::npos);

  ASSERT_EQ(run_subfab("decompose " + mesh + " -o " + quoted(dir / "b") + " --quiet --no-view").exit_code, 0);
  EXPECT_FALSE(fs::exists(dir / "b" / "view.html"));
  EXPECT_FALSE(fs::exists(dir / "b" / "assembly.html"));
  // Into a folder with pages of an earlier run: they go (they would show another result).
  ASSERT_EQ(run_subfab("decompose " + mesh + " -o " + quoted(dir / "a") + " --quiet --no-view").exit_code, 0);
  EXPECT_FALSE(fs::exists(dir / "a" / "view.html"));
  EXPECT_FALSE(fs::exists(dir / "a" / "assembly.html"));
}

TEST(AssembleCli, UnfoldWritesItsView) {
  const fs::path dir = test::temp_dir();
  ASSERT_EQ(run_subfab("unfold " + quoted(test::data_path("part.off")) + " -o " + quoted(dir / "u") + " --quiet")
                .exit_code,
            0);
  if (!std::getenv("SUBFAB_THREE_JS") && !fs::exists("/usr/share/javascript/three/three.min.js"))
    GTEST_SKIP() << "libjs-three not installed";
  EXPECT_NE(test::slurp(dir / "u" / "view.html").find("subfab unfolding"), std::string::npos);
}

TEST(AssembleCli, MissingThreeJsIsAWarningNotAFailure) {
  const fs::path dir = test::temp_dir();
  setenv("SUBFAB_THREE_JS", "/nonexistent/three.min.js", 1);
  auto r = run_subfab("decompose " + quoted(test::data_path("joint.off")) + " -o " + quoted(dir));
  unsetenv("SUBFAB_THREE_JS");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("view.html not written"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("libjs-three"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "view.html"));
  EXPECT_TRUE(fs::exists(dir / "assembly.html"));  // needs no three.js
}

TEST(AssembleCli, MoaisGluingOrderHoldsAtTwiceTheRayDensity) {
  // moai at the thesis's height: every block gets a step, and each step's
  // block is free along its axis from the blocks glued before it, checked
  // again with rays twice as dense in each direction (4x as many).
  const fs::path dir = test::temp_dir();
  ASSERT_EQ(run_subfab("decompose " + quoted(test::data_path("moai.obj")) + " -o " + quoted(dir) +
                       " --max-height 0.225 --quiet --no-view")
                .exit_code,
            0);
  const DecompositionFolder folder = read_decomposition(dir);
  std::vector<Mesh> meshes;
  GluingOptions options;
  options.rotation = folder.rotation;
  for (const DecompositionBlock& b : folder.blocks) {
    meshes.push_back(b.mesh);
    options.preferred_axis.push_back(axis_index(b.axis));
    options.volumes.push_back(b.volume);
  }
  const GluingPlan plan = plan_gluing_order(meshes, options);
  ASSERT_EQ(plan.steps.size(), folder.blocks.size());
  EXPECT_TRUE(plan.stuck.empty());
  options.resolution = 400;
  const BlockingRelation fine = compute_blocking(meshes, options);
  std::size_t num_blocking_pairs = 0;
  for (int d = 0; d < 6; ++d)
    for (bool b : fine.blocked[d]) num_blocking_pairs += b;
  EXPECT_GT(num_blocking_pairs, folder.blocks.size());  // the blocks do touch
  for (std::size_t s = 1; s < plan.steps.size(); ++s)
    for (std::size_t t = 0; t < s; ++t)
      EXPECT_FALSE(fine(plan.steps[s].axis, plan.steps[s].block, plan.steps[t].block))
          << "step " << s << " (block " << plan.steps[s].block << " from " << axis_label(plan.steps[s].axis)
          << ") passes through block " << plan.steps[t].block;
}

TEST(AssembleCli, BadArguments) {
  const fs::path dir = test::temp_dir();
  EXPECT_EQ(run_subfab("assemble " + quoted(dir / "nothing")).exit_code, 2);
  EXPECT_EQ(run_subfab("assemble " + quoted(dir) + " --size 10 --scale 2").exit_code, 1);
  EXPECT_EQ(run_subfab("assemble " + quoted(dir) + " --size -3").exit_code, 1);
  ASSERT_EQ(run_subfab("decompose " + quoted(test::data_path("joint.off")) + " -o " + quoted(dir) + " --quiet --no-view")
                .exit_code,
            0);
  auto r = run_subfab("assemble " + quoted(dir) + " --mill " + quoted(dir / "gcode"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("mill.json"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace subfab
