// SPDX-License-Identifier: GPL-3.0-or-later
// `subfab smooth`: writes the smoothed solid and prints the deviation; bad
// input exits 2 with the reason.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "subfab/checks/require_closed_solid.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::run_subfab;

TEST(SmoothCli, WritesTheSmoothedSolidAndPrintsTheDeviation) {
  const fs::path dir = test::temp_dir();
  const fs::path input = test::data_path("bunny_lowres.off");
  const fs::path out = dir / "smooth.obj";
  const auto r = run_subfab("smooth " + quoted(input) + " -o " + quoted(out) + " --passes 20 --max-deviation 0.004");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Hausdorff (symmetric)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mean (area-weighted)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("of the diagonal"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(out));
  Mesh smoothed = read_mesh(out);
  const Mesh original = read_mesh(input);
  EXPECT_EQ(smoothed.faces.size(), original.faces.size());
  EXPECT_NE(smoothed.vertices, original.vertices);
  EXPECT_NO_THROW(require_closed_solid(smoothed));

  // --json: the same measures, bounded by the cap.
  const auto j = run_subfab("smooth " + quoted(input) + " -o " + quoted(dir / "j.obj") +
                            " --passes 20 --max-deviation 0.004 --json --quiet");
  ASSERT_EQ(j.exit_code, 0) << j.output;
  const auto doc = nlohmann::json::parse(j.output);
  EXPECT_GT(doc.at("hausdorff_fraction").get<double>(), 0.0);
  EXPECT_LE(doc.at("max_displacement_fraction").get<double>(), 0.004 * (1 + 1e-12));
  EXPECT_LE(doc.at("hausdorff").get<double>(), doc.at("max_displacement").get<double>());
  EXPECT_EQ(doc.at("num_passes").get<int>(), 20);
}

TEST(SmoothCli, BadInputExitsTwoWithTheReason) {
  const fs::path dir = test::temp_dir();
  const auto open = run_subfab("smooth " + quoted(test::data_path("teapot.obj")) + " -o " + quoted(dir / "t.obj"));
  EXPECT_EQ(open.exit_code, 2) << open.output;
  EXPECT_NE(open.output.find("boundary"), std::string::npos) << open.output;
  EXPECT_FALSE(fs::exists(dir / "t.obj"));
  const auto missing = run_subfab("smooth " + quoted(dir / "nope.obj") + " -o " + quoted(dir / "n.obj"));
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  const auto usage = run_subfab("smooth " + quoted(test::data_path("bunny_lowres.off")) + " -o " +
                                quoted(dir / "u.obj") + " --weights nonsense");
  EXPECT_EQ(usage.exit_code, 1) << usage.output;
}

}  // namespace
}  // namespace subfab
