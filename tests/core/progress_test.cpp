// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/core/progress.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace subfab {
namespace {

// Stages nest (decompose's sliver stage runs the merges within the
// tolerance, their own stage): the inner one ends first, then the outer one
// is current again and ends under its own name (it printed "[] done" and an
// unnamed row in the timings table).
TEST(ConsoleProgress, NestedStagesEndUnderTheirOwnNames) {
  std::ostringstream out;
  ConsoleProgress progress(out, /*quiet=*/false, /*terminal=*/false);
  {
    StageScope outer(&progress, "slivers");
    {
      StageScope inner(&progress, "tolerance merge");
      progress.info("inner");
    }
    progress.info("outer again");
  }
  const auto timings = progress.timings();
  ASSERT_EQ(timings.size(), 2u);
  EXPECT_EQ(timings[0].first, "tolerance merge");
  EXPECT_EQ(timings[1].first, "slivers");
  const std::string text = out.str();
  EXPECT_NE(text.find("[tolerance merge] inner"), std::string::npos) << text;
  EXPECT_NE(text.find("[slivers] outer again"), std::string::npos) << text;
  EXPECT_NE(text.find("[slivers] done in"), std::string::npos) << text;
  EXPECT_EQ(text.find("[] done"), std::string::npos) << text;
  // outside any stage: info lines are the command's own
  progress.info("after");
  EXPECT_NE(out.str().find("[subfab] after"), std::string::npos);
}

}  // namespace
}  // namespace subfab
