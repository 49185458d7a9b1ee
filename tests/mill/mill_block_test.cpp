// SPDX-License-Identifier: GPL-3.0-or-later
// mill_block() on a known shape: a hemisphere on a slab, milled, simulated,
// and the simulated surface compared with the formula.
#include "subfab/mill/mill_block.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "subfab/core/parallel.h"
#include "subfab/mill/read_gcode.h"
#include "support/rs274_words.h"

namespace subfab {
namespace {

constexpr double kSide = 50.0, kSlab = 6.0, kSphere = 15.0;  // mm

double hemisphere_on_slab(double x, double y) {
  const double r2 = (x - 0.5 * kSide) * (x - 0.5 * kSide) + (y - 0.5 * kSide) * (y - 0.5 * kSide);
  return kSlab + (r2 < kSphere * kSphere ? std::sqrt(kSphere * kSphere - r2) : 0.0);
}

//! A closed height-field solid over [0, side]^2: top z = f on an n x n grid,
//! flat bottom at z = 0, vertical walls.
Mesh height_field_solid(int n, double side, const std::function<double(double, double)>& f) {
  Mesh m;
  auto top = [&](int i, int j) { return j * (n + 1) + i; };
  const int base = (n + 1) * (n + 1);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.push_back(Vec3(side * i / n, side * j / n, f(side * i / n, side * j / n)));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.push_back(Vec3(side * i / n, side * j / n, 0.0));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = top(i, j), b = top(i + 1, j), c = top(i + 1, j + 1), d = top(i, j + 1);
      m.faces.push_back({a, b, c});
      m.faces.push_back({a, c, d});
      m.faces.push_back({base + a, base + c, base + b});
      m.faces.push_back({base + a, base + d, base + c});
    }
  auto wall = [&](int p, int q) {  // boundary edge p -> q of the top, counter-clockwise seen from above
    m.faces.push_back({p, base + p, base + q});
    m.faces.push_back({p, base + q, q});
  };
  for (int i = 0; i < n; ++i) {
    wall(top(i, 0), top(i + 1, 0));
    wall(top(n, i), top(n, i + 1));
    wall(top(i + 1, n), top(i, n));
    wall(top(0, i + 1), top(0, i));
  }
  return m;
}

MillOptions test_options() {
  MillOptions o;
  o.resolution = 0.25;
  return o;
}

TEST(MillBlock, HemisphereOnASlabMatchesItsFormula) {
  const Mesh solid = height_field_solid(100, kSide, hemisphere_on_slab);
  ASSERT_GT(signed_volume(solid), 0.0);
  const MillOptions o = test_options();
  const StockSetup setup = place_in_stock(solid, 1.0, 5.0);
  EXPECT_DOUBLE_EQ(setup.stock.x, 60.0);
  EXPECT_NEAR(setup.stock.z, kSlab + kSphere + 5.0, 1e-9);
  const MilledBlock m = mill_block(setup, {"hemisphere on a slab"}, o);

  // The check's own figures: no gouge, a small scallop, the foot ring unreachable.
  EXPECT_LE(m.check.max_gouge, 0.01);
  EXPECT_EQ(m.simulation.num_rapid_cuts, 0u);
  EXPECT_LT(m.check.mean_residual, 0.03);
  // The ball (R 3) cannot reach the crease at the hemisphere's foot: a ring
  // between radii about 14.8 and 17.7 (pi (17.75^2 - 14.79^2) = 302 mm^2);
  // only its part thicker than 0.1 mm counts.
  EXPECT_GT(m.check.unreachable_area, 50.0);
  EXPECT_LT(m.check.unreachable_area, 302.0);
  EXPECT_GT(m.check.foot_area, 0.0);  // the fillet along the slab's walls

  // The picture: one pixel per cell, the unreachable ring magenta, the cap
  // and the slab green (residual below 0.02 mm), the table grey at a corner.
  ASSERT_EQ(m.picture.width, 240);
  ASSERT_EQ(m.picture.height, 240);
  auto hue = [&](int x, int y) {
    const std::uint8_t* p = &m.picture.pixels[(static_cast<std::size_t>(y) * 240 + x) * 3];
    if (p[0] > p[1] + 60 && p[2] > p[1] + 60) return 'm';
    if (p[1] > p[0] + 40 && p[1] > p[2] + 40) return 'g';
    if (p[0] == p[1] && p[1] == p[2]) return 'n';
    return '?';
  };
  EXPECT_EQ(hue(120, 120), 'g');  // the cap's top (image centre)
  EXPECT_EQ(hue(40, 120), 'g');   // the open slab
  EXPECT_EQ(hue(1, 1), 'n');      // the table, outside the block
  std::size_t ring = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 240; ++x) ring += hue(x, y) == 'm';
  EXPECT_NEAR(static_cast<double>(ring) * 0.0625, m.check.unreachable_area, 1e-6);  // every unreachable cell

  // The simulated surface against the formula, independently of the check:
  // re-simulate the G-code and sample the cap and the open slab.
  const GcodeRead program = read_gcode(m.gcode);
  HeightMap map = make_height_map(setup.stock, 0.25, setup.stock.z);
  simulate_dexels(program, {o.roughing.tool, o.finishing.tool}, map);
  const double flat_scallop = 3.0 - std::sqrt(9.0 - 0.09);  // stepover 0.6 mm on a plane
  double worst_below = 0.0, worst_above = 0.0, worst_flat = 0.0;
  int cap = 0, flat = 0;
  for (int j = 0; j < map.ny; ++j)
    for (int i = 0; i < map.nx; ++i) {
      const double x = map.x(i) - 5.0, y = map.y(j) - 5.0;  // block coordinates
      const double r = std::hypot(x - 0.5 * kSide, y - 0.5 * kSide);
      const double f = hemisphere_on_slab(x, y);
      const double s = map.at(i, j);
      if (r < 0.8 * kSphere) {
        ++cap;
        worst_below = std::max(worst_below, f - s);
        worst_above = std::max(worst_above, s - f);
      } else if (r > kSphere + 4.0 && x > 4.0 && y > 4.0 && x < kSide - 4.0 && y < kSide - 4.0) {
        ++flat;
        worst_flat = std::max(worst_flat, std::abs(s - f));
      }
    }
  ASSERT_GT(cap, 5000);
  ASSERT_GT(flat, 5000);
  EXPECT_LT(worst_below, 0.02);  // the mesh is inscribed in the sphere (chord error) plus 0.01 mm
  EXPECT_LT(worst_above, 0.1);   // scallops grow with the slope across the raster
  EXPECT_LE(worst_flat, flat_scallop + 0.002);
  EXPECT_GE(worst_flat, 0.5 * flat_scallop);
}

TEST(MillBlock, EmitsOnlyCommonRs274WordsAndIsThreadIndependent) {
  const Mesh solid = height_field_solid(40, 30.0, [](double x, double y) {
    return 4.0 + 3.0 * std::sin(x / 5.0) * std::cos(y / 7.0) + (x > 10 && x < 12 ? 5.0 : 0.0);  // with a wall
  });
  MillOptions o = test_options();
  const StockSetup setup = place_in_stock(solid, 1.0, 4.0);
  std::string gcode[2];
  for (int t = 0; t < 2; ++t) {
    ThreadLimit limit(static_cast<std::size_t>(t + 1));
    gcode[t] = mill_block(setup, {"test block"}, o).gcode;
  }
  EXPECT_EQ(gcode[0], gcode[1]);
  const MilledBlock m = mill_block(setup, {"test block"}, o);
  EXPECT_LE(m.check.max_gouge, 0.01);
  EXPECT_EQ(m.simulation.num_rapid_cuts, 0u);
  const test::Rs274Summary grbl = test::check_rs274(m.gcode, {setup.stock.x, setup.stock.y, setup.stock.z + 5.001});
  EXPECT_TRUE(grbl.problems.empty()) << grbl.problems.front();
  EXPECT_EQ(grbl.num_pauses, 1);  // the tool change
  EXPECT_EQ(grbl.last_code, "M30");
  EXPECT_FALSE(grbl.percent_wrapped);
  EXPECT_GT(grbl.num_g1, 100);

  o.gcode.dialect = GcodeDialect::LinuxCnc;
  const std::string cnc = mill_block(setup, {"test block"}, o).gcode;
  const test::Rs274Summary s = test::check_rs274(cnc, {setup.stock.x, setup.stock.y, setup.stock.z + 5.001});
  EXPECT_TRUE(s.problems.empty()) << s.problems.front();
  EXPECT_EQ(s.last_code, "M2");
  EXPECT_TRUE(s.percent_wrapped);
  EXPECT_NE(cnc.find("(MSG, change to tool 2"), std::string::npos);
  // Only comments and the program end differ.
  auto code = [](const std::string& text) {
    std::string out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
      if (!line.empty() && line[0] != '(' && line != "%" && line != "M2" && line != "M30") out += line + "\n";
    return out;
  };
  EXPECT_EQ(code(cnc), code(m.gcode));
}

TEST(MillBlock, FinishingOnlyAndFlatFinishing) {
  const Mesh solid = height_field_solid(20, 20.0, [](double x, double) { return 3.0 + 0.2 * x; });
  MillOptions o = test_options();
  o.rough = false;
  o.finishing.tool = Tool{ToolShape::Flat, 4.0};
  const MilledBlock m = mill_block(place_in_stock(solid, 1.0, 3.0), {"ramp"}, o);
  EXPECT_LE(m.check.max_gouge, 0.01);
  EXPECT_EQ(m.rough.cut, 0.0);
  EXPECT_EQ(test::check_rs274(m.gcode, {}).num_pauses, 0);
}

// A wall facing -y at 70 degrees: the x raster crosses it at an effective
// stepover of 0.6 / cos 70 = 1.75 mm; the cross pass (lines along y) follows
// it and takes its scallops down to the flat-raster height.
TEST(MillBlock, CrossPassFinishesWallsFacingY) {
  const double rise = 8.0, run = rise / std::tan(70.0 * std::acos(-1.0) / 180.0);
  const Mesh solid = height_field_solid(60, 30.0, [&](double, double y) {
    return 3.0 + rise * std::clamp((y - 12.0) / run, 0.0, 1.0);
  });
  MillOptions o = test_options();
  const StockSetup setup = place_in_stock(solid, 1.0, 4.0);
  o.finishing.cross_angle = 90.0;
  const MilledBlock x_only = mill_block(setup, {"wall"}, o);
  o.finishing.cross_angle = 50.0;
  const MilledBlock crossed = mill_block(setup, {"wall"}, o);
  EXPECT_GT(x_only.check.max_residual, 0.2);
  EXPECT_LT(crossed.check.max_residual, 0.5 * x_only.check.max_residual);
  EXPECT_LE(crossed.check.max_gouge, 0.01);
  EXPECT_EQ(crossed.simulation.num_rapid_cuts, 0u);
  EXPECT_GT(crossed.finish.cut, x_only.finish.cut);
}

}  // namespace
}  // namespace subfab
