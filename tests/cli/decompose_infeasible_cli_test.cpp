// SPDX-License-Identifier: GPL-3.0-or-later
// `subfab decompose` on a model with sharp creases in every frame it tries:
// an early, explained failure (exit code 3) instead of a failure deep in grow.
#include <gtest/gtest.h>

#include "test_support.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::run_subfab;

TEST(DecomposeCli, ImpossibleCreasesFailEarlyWithTheReason) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = test::data_path("part.off");  // CAD part, creases off the axis planes in every frame
  const auto r = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "out") + " --exact");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("no exact height-field decomposition exists in any orientation tried"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("crease edge(s)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("edge ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--no-orient"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("rejected for creases or corners"), std::string::npos) << r.output;  // orient's report
  EXPECT_EQ(r.output.find("grow"), std::string::npos) << r.output;  // failed before the grow stage
  EXPECT_FALSE(fs::exists(dir / "out" / "decomposition.json"));
  const auto kept = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "out") + " --no-orient --exact --quiet");
  EXPECT_EQ(kept.exit_code, 3) << kept.output;
  EXPECT_NE(kept.output.find("in the input frame"), std::string::npos) << kept.output;
}

}  // namespace
}  // namespace subfab
