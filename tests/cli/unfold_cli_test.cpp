// SPDX-License-Identifier: GPL-3.0-or-later
// `subfab unfold` as a user runs it.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/test_support.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;
using test::run_subfab;

using test::slurp;

using test::quoted;

// stdout's JSON object (stderr progress lines come before it).
nlohmann::json json_of(const std::string& output) {
  const auto start = output.find("{\n");
  return nlohmann::json::parse(output.substr(start, output.rfind('}') - start + 1));
}

TEST(UnfoldCli, RefusesBadInputBeforeWorking) {
  const fs::path dir = test::temp_dir();
  auto open = run_subfab("unfold " + quoted(test::data_path("teapot.obj")) + " -o " + quoted(dir / "t"));
  EXPECT_EQ(open.exit_code, 2) << open.output;
  EXPECT_NE(open.output.find("error:"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "t" / "unfold.json"));
  auto missing = run_subfab("unfold " + quoted(dir / "nope.obj") + " -o " + quoted(dir / "m"));
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
}

TEST(UnfoldCli, UsageErrors) {
  const fs::path dir = test::temp_dir();
  const std::string mesh = quoted(test::data_path("part.off"));
  EXPECT_EQ(run_subfab("unfold " + mesh + " -o " + quoted(dir) + " --sheet 12").exit_code, 1);
  EXPECT_EQ(run_subfab("unfold " + mesh + " -o " + quoted(dir) + " --delete-facets 1,x").exit_code, 1);
  EXPECT_EQ(run_subfab("unfold " + mesh + " -o " + quoted(dir) + " --granularity -1").exit_code, 1);
  EXPECT_EQ(run_subfab("unfold " + mesh).exit_code, 1);  // no -o
}

TEST(UnfoldCli, UnfoldsAndIsThreadIndependent) {
  const fs::path dir = test::temp_dir();
  const std::string mesh = quoted(test::data_path("part.off"));
  auto r1 = run_subfab("unfold " + mesh + " -o " + quoted(dir / "one") + " --granularity 1 --threads 1 --json");
  ASSERT_EQ(r1.exit_code, 0) << r1.output;
  auto r2 = run_subfab("unfold " + mesh + " -o " + quoted(dir / "two") + " --granularity 1 --threads 2 --quiet");
  ASSERT_EQ(r2.exit_code, 0) << r2.output;
  for (const char* name : {"simplified.obj", "nets.svg", "nets.dxf", "unfold.json", "preview.png"}) {
    EXPECT_TRUE(fs::exists(dir / "one" / name)) << name;
    EXPECT_EQ(slurp(dir / "one" / name), slurp(dir / "two" / name)) << name;
  }
  const auto j = json_of(r1.output);
  const auto file = nlohmann::json::parse(slurp(dir / "one" / "unfold.json"));
  EXPECT_EQ(file["summary"]["facets_final"], j["facets_final"]);
  EXPECT_EQ(file["facets"].size(), j["facets_final"]);
  EXPECT_GT(double(j["hausdorff"]), 0.0);
  EXPECT_LT(double(j["refold_error"]), 1e-9);
  EXPECT_LE(int(j["facets_final"]), int(j["facets_after_masks"]));
  // progress per stage on stderr
  EXPECT_NE(r1.output.find("delete facets"), std::string::npos);
  EXPECT_NE(r1.output.find("unfold"), std::string::npos);
}

TEST(UnfoldCli, DeleteFacetsByIdAndSheets) {
  const fs::path dir = test::temp_dir();
  const std::string mesh = quoted(test::data_path("part.off"));
  auto base = run_subfab("unfold " + mesh + " -o " + quoted(dir / "base") + " --granularity 1 --json");
  ASSERT_EQ(base.exit_code, 0) << base.output;
  const int before = json_of(base.output)["facets_final"];
  // Facet 0: deleted when its hole can be closed, otherwise kept with a warning.
  auto del = run_subfab("unfold " + mesh + " -o " + quoted(dir / "del") + " --granularity 1 --json --delete-facets 0");
  ASSERT_EQ(del.exit_code, 0) << del.output;
  const auto j = json_of(del.output);
  EXPECT_TRUE(int(j["facets_final"]) < before || int(j["deletions_refused"]) > 0);
  auto bad = run_subfab("unfold " + mesh + " -o " + quoted(dir / "bad") + " --delete-facets " +
                        std::to_string(before + 100));
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  auto sheets = run_subfab("unfold " + mesh + " -o " + quoted(dir / "sheets") + " --sheet 1000x1000 --quiet");
  EXPECT_EQ(sheets.exit_code, 0) << sheets.output;
}

}  // namespace
}  // namespace subfab
