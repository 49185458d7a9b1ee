// SPDX-License-Identifier: GPL-3.0-or-later
// `subfab decompose` reports its sliver stage (issue 17, "No slivers").
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "support/test_support.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::run_subfab;

nlohmann::json summary_of(const fs::path& folder) {
  std::ifstream in(folder / "decomposition.json");
  return nlohmann::json::parse(in).at("summary");
}

TEST(DecomposeSliversCli, TheSliverThresholdAndCountsAreRecordedAndValidated) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = test::data_path("regression/cube_tiny_diagonal_spike.obj");
  const auto within = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "within") +
                                 " --tolerance 5e-4 --json");
  ASSERT_EQ(within.exit_code, 0) << within.output;
  const nlohmann::json out = nlohmann::json::parse(within.output.substr(within.output.find('{')));
  const nlohmann::json s = summary_of(dir / "within");
  const double diagonal = nlohmann::json::parse(std::ifstream(dir / "within" / "decomposition.json"))
                              .at("input").at("bbox_diagonal").get<double>();
  // The threshold is max(1e-4 x diagonal, T) = T here, as validate's check 9.
  EXPECT_NEAR(s.at("sliver_thickness").get<double>(), 5e-4 * diagonal, 1e-12 * diagonal);
  EXPECT_EQ(s.at("num_slivers").get<int>(), 0);
  EXPECT_EQ(out.at("num_slivers").get<int>(), 0);
  EXPECT_EQ(out.at("num_slivers_merged").get<int>() + out.at("num_slivers_dropped").get<int>(),
            s.at("num_slivers_merged").get<int>() + s.at("num_slivers_dropped").get<int>());
  const auto valid = run_subfab("validate " + quoted(mesh) + " " + quoted(dir / "within"));
  EXPECT_EQ(valid.exit_code, 0) << valid.output;
  EXPECT_NE(valid.output.find("PASS  no slivers"), std::string::npos) << valid.output;
  // Exact: the threshold is 1e-4 x diagonal, nothing is removed.
  const fs::path joint = test::data_path("joint.off");
  const auto exact = run_subfab("decompose " + quoted(joint) + " -o " + quoted(dir / "exact") + " --quiet");
  ASSERT_EQ(exact.exit_code, 0) << exact.output;
  const nlohmann::json e = summary_of(dir / "exact");
  const double joint_diagonal = nlohmann::json::parse(std::ifstream(dir / "exact" / "decomposition.json"))
                                    .at("input").at("bbox_diagonal").get<double>();
  EXPECT_NEAR(e.at("sliver_thickness").get<double>(), 1e-4 * joint_diagonal, 1e-12 * joint_diagonal);
  EXPECT_EQ(e.at("num_slivers").get<int>(), 0);
  EXPECT_EQ(e.at("num_slivers_merged").get<int>(), 0);
  EXPECT_EQ(e.at("num_slivers_dropped").get<int>(), 0);
}

//! Decomposes data/`name` within `tolerance` and expects no sliver left,
//! at least one decomposed again with its neighbours, and validate to pass
//! checks 9 and 10.
void expect_sliver_decomposed_again(const std::string& name, const std::string& tolerance,
                                    const std::string& extra = "") {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = test::data_path(name);
  const auto r = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "out") + " --tolerance " + tolerance +
                            " --json --threads 2 --no-view" + extra);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json out = nlohmann::json::parse(r.output.substr(r.output.find('{')));
  EXPECT_EQ(out.at("num_slivers").get<int>(), 0);
  EXPECT_GE(out.at("num_slivers_recarved").get<int>(), 1);
  const auto valid = run_subfab("validate " + quoted(mesh) + " " + quoted(dir / "out") + " --threads 2");
  EXPECT_EQ(valid.exit_code, 0) << valid.output;
  EXPECT_NE(valid.output.find("PASS  no slivers"), std::string::npos) << valid.output;
  EXPECT_NE(valid.output.find("PASS  within the tolerance"), std::string::npos) << valid.output;
}

TEST(DecomposeSliversCli, ASliverTheExactCarveGivesBackIsDecomposedAgainWithinTheTolerance) {
  // Regression (issue 17, "no slivers"): turbine.off at --tolerance 1e-3
  // kept one sliver (0.99 T thick, a 0.02 x 0.08 x 0.003 slab under a
  // flange; validate check 9 failed): no drop (the input near it lies 2 T
  // from the other blocks), no merge into a milled shape within T, and the
  // exact re-decomposition of it with either neighbour gave it back. With
  // one neighbour, the union decomposed again under its own allowances
  // (then milled and measured) gives 2 blocks, neither a sliver.
  expect_sliver_decomposed_again("turbine.off", "1e-3");
}

TEST(DecomposeSliversCli, ASliverNoSingleNeighbourTakesIsDecomposedAgainWithTwo) {
  // Regression (issue 17, "no slivers"): spot.obj at --tolerance 5e-4 kept
  // one sliver (block 1, a 0.027 x 0.018 x 0.002 plate, 0.6 T thick on
  // average; validate check 9 failed): with either of its two largest
  // neighbours, exactly and at every allowance level, the carve gave a
  // sliver back (or a milled shape 1.4 T from the input). With both at
  // once, the union's exact decomposition gives 2 blocks, neither a sliver
  // (32 blocks in all instead of 33). Since session 35 the rounds within
  // the tolerance carry the passing blocks over and spot has no such
  // sliver; `--tolerance-locate -1` keeps the rounds that made it.
  expect_sliver_decomposed_again("spot.obj", "5e-4", " --tolerance-locate -1");
}

TEST(DecomposeSliversCli, AtTheDefaultAnExactSliverIsDecomposedAgainWithTwoNeighbours) {
  // Regression (issue 17, "no slivers"): fandisk's face x = 0 has 9 vertices
  // at x = 1e-6 and 2e-6 (CAD noise); its exact decomposition (11 blocks)
  // kept the 2e-6 slab between the box planes x = 0 and x = 2e-6 as a block,
  // 2.6e-7 x diagonal thick, and validate's check 9 failed. Then the exact
  // blocks' slivers sent it to the fallback tolerance (5e-4); now step 9c
  // decomposes the slab again with two of its neighbours (8 and 4) exactly:
  // 11 exact blocks, no sliver, nothing deviates, no fallback. (Since
  // session 25 the orientation snaps that noise within the file's rounding:
  // 6 blocks, no slab. --no-orient keeps the same frame without the snap, so
  // step 9c is still exercised here.)
  const fs::path dir = test::temp_dir();
  const fs::path mesh = test::data_path("fandisk.obj");
  const auto r =
      run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "out") + " --no-orient --json --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json out = nlohmann::json::parse(r.output.substr(r.output.find('{')));
  EXPECT_TRUE(out.at("tolerance_fallback").is_null()) << r.output;
  EXPECT_EQ(out.at("tolerance").get<double>(), 0.0);
  EXPECT_EQ(out.at("num_slivers").get<int>(), 0);
  EXPECT_GE(out.at("num_slivers_recarved").get<int>(), 1);
  const auto valid = run_subfab("validate " + quoted(mesh) + " " + quoted(dir / "out") + " --threads 2");
  EXPECT_EQ(valid.exit_code, 0) << valid.output;
  EXPECT_NE(valid.output.find("PASS  no slivers"), std::string::npos) << valid.output;
}

}  // namespace
}  // namespace subfab
