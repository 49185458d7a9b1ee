// SPDX-License-Identifier: GPL-3.0-or-later
// finish_toolpath(): every cutting move stays within the planner's tolerance
// of the drop-cutter surface, sampled densely along the move, including on
// the five triangles where max planck's block 44 was gouged by 0.027 mm.
#include "subfab/mill/finish_toolpath.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace subfab {
namespace {

//! Largest depth (mm) by which a cutting move of `path` goes below the
//! drop-cutter surface, sampled every `spacing` mm along each move within
//! the xy box [x0, x1] x [y0, y1].
double deepest_dip(const Toolpath& path, const TriangleGrid& grid, double spacing, double x0, double y0, double x1,
                   double y1) {
  double worst = 0.0;
  Vec3 at(0.0, 0.0, path.safe_z);
  for (const Move& m : path.moves) {
    const Vec3 a = at;
    at = m.to;
    if (m.kind != MoveKind::Cut) continue;
    if (std::max(a.x(), m.to.x()) < x0 || std::min(a.x(), m.to.x()) > x1 || std::max(a.y(), m.to.y()) < y0 ||
        std::min(a.y(), m.to.y()) > y1)
      continue;
    const int n = std::max(1, static_cast<int>(std::ceil((m.to - a).head<2>().norm() / spacing)));
    for (int i = 0; i <= n; ++i) {
      const Vec3 p = a + (m.to - a) * (static_cast<double>(i) / n);
      worst = std::max(worst, drop_cutter(grid, path.tool, p.x(), p.y()) - p.z());
    }
  }
  return worst;
}

// Max planck (Table 4.1, no height limit) at --size 200, block 44 (-z): the
// five triangles in reach of the raster line y = 88.141 near x = 76, in the
// machine frame (mm), and that block's stock (which sets the raster). The
// drop-cutter height along the 0.25 mm segment from x = 76.031 to 75.782
// crosses its chord near the midpoint (S-shaped: a crease, then a ridge), so
// a midpoint-only test accepted the chord and the ball cut 0.04 mm into the
// ridge (0.027 mm at the nearest simulation cell).
TEST(FinishToolpath, StaysOnTheDropCutterSurfaceAcrossAnSShapedSegment) {
  Mesh m;
  m.vertices = {{73.349028, 86.254722, 9.103300},  {72.955810, 88.531091, 10.035750},
                {72.946561, 87.669747, 10.829067}, {72.834448, 87.071262, 11.822906},
                {72.573723, 89.177933, 12.600817}, {73.356849, 87.371810, 8.435605},
                {72.560213, 89.862925, 11.699654}};
  m.faces = {{0, 1, 2}, {3, 2, 4}, {0, 5, 1}, {2, 1, 6}, {4, 2, 6}};
  const Stock stock{84.756352, 104.930191, 75.890145};
  const TriangleGrid grid(m, 3.0);
  const FinishingOptions o;
  const Toolpath path = finish_toolpath(grid, stock, o);
  // The segment that was gouged is in the path's box.
  EXPECT_LE(deepest_dip(path, grid, 0.002, 65.0, 80.0, 85.0, 97.0), o.tolerance + 1e-6);
}

// A field of steep bumps and creases (every slope, both raster directions).
TEST(FinishToolpath, StaysWithinToleranceOnSteepBumps) {
  Mesh m;
  const int n = 24;
  const double side = 24.0;
  auto f = [](double x, double y) { return 3.0 + 2.5 * std::sin(1.3 * x) * std::cos(0.9 * y) + (x > 9 ? 4.0 : 0.0); };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.push_back(Vec3(side * i / n, side * j / n, f(side * i / n, side * j / n)));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      m.faces.push_back({a, b, c});
      m.faces.push_back({a, c, d});
    }
  const TriangleGrid grid(m, 3.0);
  const FinishingOptions o;
  const Toolpath path = finish_toolpath(grid, Stock{side, side, 12.0}, o);
  EXPECT_LE(deepest_dip(path, grid, 0.01, 0.0, 0.0, side, side), o.tolerance + 1e-6);
}

}  // namespace
}  // namespace subfab
