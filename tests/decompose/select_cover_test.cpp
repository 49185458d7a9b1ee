// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/select_cover.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "subfab/core/error.h"

namespace subfab {
namespace {

using Lists = std::vector<std::vector<int>>;

bool covers_all(const Lists& covered, std::size_t num_faces, const std::vector<int>& selected) {
  std::vector<char> hit(num_faces, 0);
  for (int b : selected)
    for (int f : covered[static_cast<std::size_t>(b)]) hit[static_cast<std::size_t>(f)] = 1;
  return std::all_of(hit.begin(), hit.end(), [](char c) { return c != 0; });
}

//! Smallest cover size by enumerating all subsets (num boxes <= 20).
std::size_t brute_force_minimum(const Lists& covered, std::size_t num_faces) {
  const std::size_t n = covered.size();
  std::size_t best = n + 1;
  for (std::uint32_t mask = 0; mask < (1u << n); ++mask) {
    const auto k = static_cast<std::size_t>(std::popcount(mask));
    if (k >= best) continue;
    std::vector<int> sel;
    for (std::size_t b = 0; b < n; ++b)
      if (mask & (1u << b)) sel.push_back(static_cast<int>(b));
    if (covers_all(covered, num_faces, sel)) best = k;
  }
  return best;
}

//! Random instance where every face is covered (face f always lies in box f % n).
Lists random_instance(std::size_t num_boxes, std::size_t num_faces, double density, unsigned seed) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution in(density);
  Lists covered(num_boxes);
  for (std::size_t f = 0; f < num_faces; ++f)
    for (std::size_t b = 0; b < num_boxes; ++b)
      if (b == f % num_boxes || in(rng)) covered[b].push_back(static_cast<int>(f));
  return covered;
}

TEST(SelectCover, MatchesBruteForceOnSmallRandomInstances) {
  for (unsigned seed = 1; seed <= 12; ++seed) {
    const std::size_t num_boxes = 10 + seed % 6, num_faces = 25 + 3 * seed;
    const Lists covered = random_instance(num_boxes, num_faces, 0.18, seed);
    const CoverResult r = select_cover(covered, num_faces, {});
    EXPECT_TRUE(covers_all(covered, num_faces, r.selected)) << "seed " << seed;
    EXPECT_EQ(r.selected.size(), brute_force_minimum(covered, num_faces)) << "seed " << seed;
    EXPECT_TRUE(r.optimal);
    EXPECT_TRUE(std::is_sorted(r.selected.begin(), r.selected.end()));
  }
}

// Two rows of 2^k - 1 faces; "row" boxes cover one row each, "column block"
// boxes cover blocks of 2^(k-1), ..., 2, 1 faces in both rows. Greedy takes
// the column blocks (k boxes); the optimum is the 2 row boxes.
TEST(SelectCover, BeatsGreedyOnClassicInstance) {
  const int k = 5;
  const int row_len = (1 << k) - 1;
  const auto num_faces = static_cast<std::size_t>(2 * row_len);
  Lists covered;
  std::vector<int> top, bottom;
  for (int i = 0; i < row_len; ++i) {
    top.push_back(i);
    bottom.push_back(row_len + i);
  }
  int start = 0;
  for (int size = 1 << (k - 1); size >= 1; size /= 2) {
    std::vector<int> block;
    for (int i = start; i < start + size; ++i) block.push_back(i);
    for (int i = start; i < start + size; ++i) block.push_back(row_len + i);
    covered.push_back(block);
    start += size;
  }
  covered.push_back(top);     // box k
  covered.push_back(bottom);  // box k + 1
  const CoverResult r = select_cover(covered, num_faces, {});
  EXPECT_EQ(r.selected, (std::vector<int>{k, k + 1}));
  EXPECT_TRUE(r.optimal);
  EXPECT_EQ(r.lower_bound, 2.0);
}

TEST(SelectCover, DominatedBoxesAreNeverChosenAndTiesKeepLowerIndex) {
  // box 0 = {0,1}  (dominated by box 2)
  // box 1 = {2,3,4}, box 3 = {2,3,4} (equal: box 1 kept)
  // box 2 = {0,1,5}
  const Lists covered = {{0, 1}, {2, 3, 4}, {0, 1, 5}, {2, 3, 4}};
  const CoverResult r = select_cover(covered, 6, {});
  EXPECT_EQ(r.selected, (std::vector<int>{1, 2}));
  EXPECT_EQ(r.num_reduced_boxes, 0u);  // everything was decided by reduction
  EXPECT_EQ(r.num_forced, 2u);
}

TEST(SelectCover, CostsCountBlocksNotBoxes) {
  // Box 0 covers everything but stands for 3 blocks; boxes 1 and 2 (one
  // block each) cover it together: 2 blocks beat 1 box of 3.
  const Lists covered = {{0, 1, 2, 3}, {0, 1}, {2, 3}};
  CoverOptions o;
  EXPECT_EQ(select_cover(covered, 4, o).selected, (std::vector<int>{0}));
  o.cost = {3, 1, 1};
  const CoverResult r = select_cover(covered, 4, o);
  EXPECT_EQ(r.selected, (std::vector<int>{1, 2}));
  EXPECT_TRUE(r.optimal);
  EXPECT_EQ(r.lower_bound, 2.0);
  // Boxes 1 and 2 have rows that are subsets of dearer box 0's: not
  // dominated by it (else box 0 alone, cost 3, would be forced).
  o.cost = {3, 1, 1};
  EXPECT_EQ(select_cover({{0, 1, 2, 3, 4}, {0, 1, 4}, {2, 3}}, 5, o).selected, (std::vector<int>{1, 2}));
  o.cost = {0, 1, 1};
  EXPECT_THROW(select_cover(covered, 4, o), InvalidArgumentError);
  o.cost = {1, 1};
  EXPECT_THROW(select_cover(covered, 4, o), InvalidArgumentError);
}

TEST(SelectCover, ReductionKeepsOptimalityOnOverlappingInstance) {
  // A 4-cycle of boxes over 4 faces plus subsets: optimum 2.
  const Lists covered = {{0, 1}, {1, 2}, {2, 3}, {0, 3}, {1}, {3}, {0}};
  const CoverResult r = select_cover(covered, 4, {});
  EXPECT_EQ(r.selected.size(), 2u);
  EXPECT_TRUE(covers_all(covered, 4, r.selected));
  EXPECT_EQ(r.num_reduced_boxes, 4u);  // the singletons are dominated; the ILP gets the cycle
  EXPECT_EQ(r.num_reduced_rows, 4u);
}

TEST(SelectCover, UncoveredFaceIsNamed) {
  const Lists covered = {{0, 1}, {1, 3}};
  try {
    select_cover(covered, 4, {});
    FAIL() << "expected AlgorithmError";
  } catch (const AlgorithmError& e) {
    EXPECT_NE(std::string(e.what()).find("face 2"), std::string::npos) << e.what();
  }
}

TEST(SelectCover, RejectsBadArguments) {
  EXPECT_THROW(select_cover({{0, 5}}, 3, {}), InvalidArgumentError);
  EXPECT_THROW(select_cover({{1, 0}}, 3, {}), InvalidArgumentError);
  CoverOptions zero_time;
  zero_time.time_limit_s = 0;
  EXPECT_THROW(select_cover({{0, 1, 2}}, 3, zero_time), InvalidArgumentError);
  CoverOptions wrong_size;
  wrong_size.preference = {1.0, 2.0};
  EXPECT_THROW(select_cover({{0, 1, 2}}, 3, wrong_size), InvalidArgumentError);
}

TEST(SelectCover, PreferenceBreaksTiesWithoutAddingBoxes) {
  // Covers of size 2: {0,1} or {2,3}; {4} alone would need 3 with others.
  const Lists covered = {{0, 1, 2}, {3, 4, 5}, {0, 1, 3}, {2, 4, 5}, {0}};
  const CoverResult plain = select_cover(covered, 6, {});
  EXPECT_EQ(plain.selected.size(), 2u);
  CoverOptions options;
  options.preference = {1, 1, 5, 5, 100};
  const CoverResult prefer_23 = select_cover(covered, 6, options);
  EXPECT_EQ(prefer_23.selected, (std::vector<int>{2, 3}));
  options.preference = {5, 5, 1, 1, 100};
  const CoverResult prefer_01 = select_cover(covered, 6, options);
  EXPECT_EQ(prefer_01.selected, (std::vector<int>{0, 1}));
}

TEST(SelectCover, LargerInstanceIsDeterministicAndValid) {
  const std::size_t num_boxes = 150, num_faces = 1500;
  const Lists covered = random_instance(num_boxes, num_faces, 0.02, 7);
  const CoverResult a = select_cover(covered, num_faces, {});
  const CoverResult b = select_cover(covered, num_faces, {});
  EXPECT_EQ(a.selected, b.selected);
  EXPECT_TRUE(covers_all(covered, num_faces, a.selected));
  EXPECT_GT(a.num_reduced_boxes, 0u);  // the ILP did real work
  EXPECT_LE(a.lower_bound, static_cast<double>(a.selected.size()));
  // No chosen box is redundant.
  for (std::size_t k = 0; k < a.selected.size(); ++k) {
    std::vector<int> rest = a.selected;
    rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(k));
    EXPECT_FALSE(covers_all(covered, num_faces, rest));
  }
}

}  // namespace
}  // namespace subfab
