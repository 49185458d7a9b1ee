// SPDX-License-Identifier: GPL-3.0-or-later
// swept_tool_height() against sampling along the move.
#include "subfab/mill/simulate_dexels.h"

#include "subfab/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace subfab {
namespace {

TEST(SimulateDexels, SweptHeightIsTheMinimumAlongTheMove) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-4.0, 4.0), h(0.0, 5.0);
  for (const Tool& tool : {Tool{ToolShape::Ball, 6.0}, Tool{ToolShape::Flat, 8.0}})
    for (int k = 0; k < 400; ++k) {
      const Vec3 a(u(rng), u(rng), h(rng)), b(u(rng), u(rng), h(rng));
      const double x = u(rng), y = u(rng);
      double sampled = std::numeric_limits<double>::infinity();
      for (int i = 0; i <= 20000; ++i) {
        const Vec3 p = a + (b - a) * (i / 20000.0);
        const double d = std::hypot(p.x() - x, p.y() - y);
        if (d <= tool.radius()) sampled = std::min(sampled, p.z() + tool_profile(tool, d));
      }
      const double exact = swept_tool_height(tool, a, b, x, y);
      if (std::isinf(sampled)) {
        EXPECT_TRUE(std::isinf(exact) || exact >= std::min(a.z(), b.z())) << k;
        continue;
      }
      EXPECT_LE(exact, sampled + 1e-9) << k;
      EXPECT_GE(exact, sampled - 2e-3) << k;
    }
}

TEST(SimulateDexels, ReadsAndMillsAProgram) {
  const Stock stock{20, 10, 5};
  HeightMap map = make_height_map(stock, 0.5, 5.0);
  const GcodeRead program = read_gcode("G21 G90\nG0 Z10.000\nG0 X0.000 Y5.000\nS1000.000 M3\nG1 Z2.000 F100.000\nG1 X20.000\nM5\nM2\n");
  ASSERT_EQ(program.moves.size(), 2u);  // the first G0 starts from an unknown x, y
  const SimulationStats stats = simulate_dexels(program, {Tool{ToolShape::Flat, 4.0}}, map);
  EXPECT_EQ(stats.num_rapid_cuts, 0u);
  EXPECT_DOUBLE_EQ(map.at(10, 10), 2.0);   // (5.25, 5.25): under the slot
  EXPECT_DOUBLE_EQ(map.at(10, 16), 5.0);   // y = 8.25: beyond the 2 mm radius
  EXPECT_THROW(read_gcode("G20\n"), IoError);
  EXPECT_THROW(read_gcode("G0 X1 Y2 Z3\nG1 X4\n"), IoError);  // G1 without a feed
  EXPECT_THROW(read_gcode("G2 X1 Y1 I1 J0\n"), IoError);
}

}  // namespace
}  // namespace subfab
