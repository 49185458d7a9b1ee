// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

namespace subfab {
namespace {

TEST(ParallelFor, VisitsEveryIndexOnce) {
  std::vector<std::atomic<int>> hits(10000);
  parallel_for(0, hits.size(), [&](std::size_t i) { hits[i]++; });
  for (const auto& h : hits) EXPECT_EQ(h.load(), 1);
}

TEST(ParallelFor, RethrowsTheErrorOfTheSmallestIndex) {
  try {
    parallel_for(0, 1000, [](std::size_t i) {
      if (i % 100 == 7) throw std::runtime_error(std::to_string(i));
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "7");
  }
}

TEST(ParallelFor, ThreadLimitApplies) {
  ThreadLimit limit(1);
  EXPECT_EQ(max_threads(), 1u);
}

}  // namespace
}  // namespace subfab
