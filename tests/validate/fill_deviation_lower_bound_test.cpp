// SPDX-License-Identifier: GPL-3.0-or-later
// The sampled lower bound of the fill deviation (issue 17): boxes sticking
// out of a cube, with known distances.
#include "subfab/validate/fill_deviation_lower_bound.h"

#include <gtest/gtest.h>

#include <limits>

#include "subfab/core/error.h"
#include "support/box_shapes.h"

namespace subfab {
namespace {

using test::make_box_mesh;

constexpr double kInf = std::numeric_limits<double>::infinity();

// S = [0, 10]^3; F = [2, 4]^2 x [5, 13] sticks out 3 above S's top: its top
// face lies 3 from S, every other point of it outside S less.
TEST(FillDeviationLowerBound, AColumnSticking3OutOfACubeIsBoundedBy3) {
  const Mesh solid = make_box_mesh(Vec3(0, 0, 0), Vec3(10, 10, 10));
  const Mesh column = make_box_mesh(Vec3(2, 2, 5), Vec3(4, 4, 13));
  const std::vector<double> b = fill_deviation_lower_bounds(solid, {&column}, {std::nullopt}, kInf);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_DOUBLE_EQ(b[0], 3.0);
  // The search stops past `stop`, still above it.
  const double stopped = fill_deviation_lower_bounds(solid, {&column}, {std::nullopt}, 1.0)[0];
  EXPECT_GT(stopped, 1.0);
  EXPECT_LE(stopped, 3.0);
  // Fill boxes that meet none of its faces: nothing sampled.
  const std::vector<BoundingBox> away{{Vec3(20, 20, 20), Vec3(21, 21, 21)}};
  EXPECT_EQ(fill_deviation_lower_bounds(solid, {&column}, {away}, kInf)[0], 0.0);
  // Not asked: 0.
  EXPECT_EQ(fill_deviation_lower_bounds(solid, {&column}, {std::nullopt}, kInf, {0})[0], 0.0);
  EXPECT_THROW(fill_deviation_lower_bounds(solid, {&column}, {}, kInf), InvalidArgumentError);
}

// Collecting the far points: the search goes on past `stop` (the bound is
// then the maximum, 3), and every point collected lies farther than `stop`
// from S: on F above z = 11 (its top, and its sides' samples there).
TEST(FillDeviationLowerBound, FarPointsAreEverySampleBeyondTheStop) {
  const Mesh solid = make_box_mesh(Vec3(0, 0, 0), Vec3(10, 10, 10));
  const Mesh column = make_box_mesh(Vec3(2, 2, 5), Vec3(4, 4, 13));
  std::vector<std::vector<Vec3>> far;
  const std::vector<double> b = fill_deviation_lower_bounds(solid, {&column}, {std::nullopt}, 1.0, {}, &far);
  EXPECT_DOUBLE_EQ(b.at(0), 3.0);
  ASSERT_EQ(far.size(), 1u);
  ASSERT_FALSE(far[0].empty());
  bool top = false;
  for (const Vec3& p : far[0]) {
    EXPECT_GT(p.z(), 11.0) << p.transpose();
    EXPECT_TRUE(p.x() >= 2 && p.x() <= 4 && p.y() >= 2 && p.y() <= 4) << p.transpose();
    top = top || p.z() == 13.0;
  }
  EXPECT_TRUE(top);
  // A stop above every distance: nothing collected.
  fill_deviation_lower_bounds(solid, {&column}, {std::nullopt}, 3.0, {}, &far);
  EXPECT_TRUE(far.at(0).empty());
}

// A second filled box G = [2, 4]^2 x [13, 15] on top of F: F's top is then
// a contact face inside the model made (not on its surface), so F's bound
// drops from 3 to its sides' samples; G's own top lies 5 from S. A box inside S deviates 0.
TEST(FillDeviationLowerBound, AFaceAgainstAnotherFillIsNotOnTheModelMade) {
  const Mesh solid = make_box_mesh(Vec3(0, 0, 0), Vec3(10, 10, 10));
  const Mesh column = make_box_mesh(Vec3(2, 2, 5), Vec3(4, 4, 13));
  const Mesh cap = make_box_mesh(Vec3(2, 2, 13), Vec3(4, 4, 15));
  const Mesh inner = make_box_mesh(Vec3(6, 6, 1), Vec3(8, 8, 9));
  const std::vector<double> b = fill_deviation_lower_bounds(solid, {&column, &cap, &inner},
                                                            {std::nullopt, std::nullopt, std::nullopt}, kInf);
  ASSERT_EQ(b.size(), 3u);
  EXPECT_DOUBLE_EQ(b[0], 1.0);  // its sides' highest samples below G, at z = 11 (the grid: z = 5 + 8 i / 4)
  EXPECT_DOUBLE_EQ(b[1], 5.0);
  EXPECT_EQ(b[2], 0.0);
}

// The other way: a filled block that buries the input. S = [0, 10]^3 with
// a 4 x 4 x 4 notch cut from its top (x, y in [3, 7], z in [6, 10]); the
// milled shape F = [1, 9]^2 x [2, 10] fills it: the notch floor's centre
// (5, 5, 6) lies 4 inside F (the buried input: 4), while F's top over the
// notch lies at most 2 from S (the notch's walls): the bound is 4.
TEST(FillDeviationLowerBound, AFillThatBuriesTheInputIsBoundedByHowDeep) {
  const Mesh solid = test::make_notched_cube();
  const Mesh fill = make_box_mesh(Vec3(1, 1, 2), Vec3(9, 9, 10));
  const double b = fill_deviation_lower_bounds(solid, {&fill}, {std::nullopt}, kInf)[0];
  EXPECT_DOUBLE_EQ(b, 4.0);
}

}  // namespace
}  // namespace subfab
