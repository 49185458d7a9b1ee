// SPDX-License-Identifier: GPL-3.0-or-later
// `subfab decompose` and `subfab validate` as a user runs them.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "test_support.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;
using test::run_subfab;

using test::slurp;

using test::quoted;

TEST(DecomposeCli, DecomposesValidatesAndIsThreadIndependent) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = test::data_path("joint.off");
  auto r1 = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "one") + " --threads 1 --quiet");
  ASSERT_EQ(r1.exit_code, 0) << r1.output;
  auto r2 = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "two") + " --threads 2 --json");
  ASSERT_EQ(r2.exit_code, 0) << r2.output;
  EXPECT_NE(r2.output.find("\"num_blocks\""), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "one" / "blocks" / "block_000.obj"));
  EXPECT_TRUE(fs::exists(dir / "one" / "mill" / "block_000.stl"));
  // Byte-identical outputs apart from the timings.
  for (const auto& entry : fs::recursive_directory_iterator(dir / "one")) {
    if (!entry.is_regular_file()) continue;
    const fs::path rel = fs::relative(entry.path(), dir / "one");
    std::string a = slurp(entry.path()), b = slurp(dir / "two" / rel);
    if (rel == "decomposition.json") {
      a = a.substr(0, a.find("\"timings_s\""));
      b = b.substr(0, b.find("\"timings_s\""));
    }
    EXPECT_EQ(a, b) << rel;
  }
  auto v = run_subfab("validate " + quoted(mesh) + " " + quoted(dir / "one"));
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_NE(v.output.find("all checks passed"), std::string::npos) << v.output;
}

TEST(DecomposeCli, ValidateFailsOnATamperedDecomposition) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = test::data_path("joint.off");
  ASSERT_EQ(run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir) + " --quiet").exit_code, 0);
  ASSERT_TRUE(fs::exists(dir / "blocks" / "block_001.obj"));  // joint.off needs two blocks
  EXPECT_EQ(run_subfab("validate " + quoted(mesh) + " " + quoted(dir) + " --quiet").exit_code, 0);
  // Point block 0 at block 1's files: a duplicate (overlap) and a gap.
  std::string tampered = slurp(dir / "decomposition.json");
  const auto first = tampered.find("\"blocks/block_000.obj\"");
  ASSERT_NE(first, std::string::npos);
  tampered.replace(first, 22, "\"blocks/block_001.obj\"");
  std::ofstream(dir / "decomposition.json", std::ios::binary) << tampered;
  auto v = run_subfab("validate " + quoted(mesh) + " " + quoted(dir));
  EXPECT_EQ(v.exit_code, 3) << v.output;
  EXPECT_NE(v.output.find("FAIL"), std::string::npos);
}

TEST(DecomposeCli, RefusesAnOpenMeshAndBadOptions) {
  const fs::path dir = test::temp_dir();
  auto open = run_subfab("decompose " + quoted(test::data_path("teapot.obj")) + " -o " + quoted(dir));
  EXPECT_EQ(open.exit_code, 2) << open.output;
  auto missing = run_subfab("decompose " + quoted(dir / "nope.obj") + " -o " + quoted(dir));
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  auto machine = run_subfab("decompose " + quoted(test::data_path("cross.off")) + " -o " + quoted(dir) +
                            " --machine 1,2");
  EXPECT_EQ(machine.exit_code, 1) << machine.output;
  auto height = run_subfab("decompose " + quoted(test::data_path("cross.off")) + " -o " + quoted(dir) +
                           " --max-height -3");
  EXPECT_EQ(height.exit_code, 1) << height.output;
  auto no_dir = run_subfab("validate " + quoted(test::data_path("cross.off")) + " " + quoted(dir / "absent"));
  EXPECT_EQ(no_dir.exit_code, 2) << no_dir.output;
  auto help = run_subfab("decompose --help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* option : {"--max-height", "--max-height-abs", "--machine", "--no-orient", "--grid-factor",
                             "--threads", "--json", "--quiet"})
    EXPECT_NE(help.output.find(option), std::string::npos) << option;
}

}  // namespace
}  // namespace subfab
