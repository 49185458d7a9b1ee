// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/lattice_directions.h"

#include <gtest/gtest.h>

#include <set>

namespace subfab {
namespace {

TEST(LatticeDirections, AreThe26DistinctNonZeroDirections) {
  const auto& dirs = lattice_directions();
  std::set<std::array<int, 3>> unique(dirs.begin(), dirs.end());
  EXPECT_EQ(unique.size(), 26u);
  EXPECT_EQ(unique.count({0, 0, 0}), 0u);
}

TEST(LatticeDirections, ClassifiesNormals) {
  const auto i = lattice_direction_index(Vec3(2, 2, 0));
  ASSERT_TRUE(i.has_value());
  EXPECT_EQ(lattice_directions()[static_cast<std::size_t>(*i)], (std::array<int, 3>{1, 1, 0}));
  EXPECT_FALSE(lattice_direction_index(Vec3(1, 2, 0)).has_value());
  EXPECT_FALSE(lattice_direction_index(Vec3(0, 0, 0)).has_value());
}

}  // namespace
}  // namespace subfab
