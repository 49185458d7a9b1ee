// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mill/simulate_dexels.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "subfab/core/error.h"

namespace subfab {

HeightMap make_height_map(const Stock& stock, double resolution, double height) {
  if (!(resolution > 0.0)) throw InvalidArgumentError("simulation resolution must be positive (mm)");
  HeightMap map;
  map.resolution = resolution;
  map.nx = std::max(1, static_cast<int>(std::ceil(stock.x / resolution - 1e-9)));
  map.ny = std::max(1, static_cast<int>(std::ceil(stock.y / resolution - 1e-9)));
  map.z.assign(static_cast<std::size_t>(map.nx) * map.ny, height);
  return map;
}

double swept_tool_height(const Tool& tool, const Vec3& a, const Vec3& b, double x, double y) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double r = tool.radius();
  const double ux = b.x() - a.x(), uy = b.y() - a.y();
  const double len = std::hypot(ux, uy);
  const double qx = x - a.x(), qy = y - a.y();
  const bool ball = tool.shape == ToolShape::Ball;
  if (len < 1e-12) {  // vertical move
    const double d2 = qx * qx + qy * qy;
    if (d2 > r * r) return kInf;
    return std::min(a.z(), b.z()) + (ball ? r - std::sqrt(r * r - d2) : 0.0);
  }
  const double par = (qx * ux + qy * uy) / len;
  const double perp2 = std::max(0.0, qx * qx + qy * qy - par * par);
  if (perp2 > r * r) return kInf;
  const double half = std::sqrt(r * r - perp2);  // the tool covers (x, y) for tau in [par - half, par + half]
  const double lo = std::max(0.0, par - half), hi = std::min(len, par + half);
  if (lo > hi) return kInf;
  const double m = (b.z() - a.z()) / len;
  if (!ball) return a.z() + m * (m > 0 ? lo : hi);
  // Ball: centre height a.z + r + m tau minus sqrt(r^2 - perp2 - (tau - par)^2), convex in tau.
  const double tau = std::clamp(par - m * half / std::sqrt(1.0 + m * m), lo, hi);
  const double d = tau - par;
  return a.z() + r + m * tau - std::sqrt(std::max(0.0, half * half - d * d));
}

SimulationStats simulate_dexels(const GcodeRead& program, const std::vector<Tool>& tools, HeightMap& map) {
  SimulationStats stats;
  const double res = map.resolution;
  for (const GcodeMove& mv : program.moves) {
    if (mv.tool < 0 || static_cast<std::size_t>(mv.tool) >= tools.size())
      throw InvalidArgumentError("G-code line " + std::to_string(mv.line) + ": tool " + std::to_string(mv.tool + 1) +
                                 " used but only " + std::to_string(tools.size()) + " tools given");
    const Tool& tool = tools[static_cast<std::size_t>(mv.tool)];
    ++stats.num_moves;
    const double r = tool.radius();
    const int i0 = std::max(0, static_cast<int>(std::floor((std::min(mv.from.x(), mv.to.x()) - r) / res - 0.5)));
    const int i1 = std::min(map.nx - 1, static_cast<int>(std::ceil((std::max(mv.from.x(), mv.to.x()) + r) / res - 0.5)));
    const int j0 = std::max(0, static_cast<int>(std::floor((std::min(mv.from.y(), mv.to.y()) - r) / res - 0.5)));
    const int j1 = std::min(map.ny - 1, static_cast<int>(std::ceil((std::max(mv.from.y(), mv.to.y()) + r) / res - 0.5)));
    const double bottom = std::min(mv.from.z(), mv.to.z());
    double removed = 0.0;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        double& h = map.at(i, j);
        if (h <= bottom) continue;  // the tool stays above this column
        const double z = swept_tool_height(tool, mv.from, mv.to, map.x(i), map.y(j));
        if (z < h) {
          removed = std::max(removed, h - z);
          h = z;
        }
      }
    if (mv.rapid && removed > 1e-9) {
      ++stats.num_rapid_cuts;
      stats.max_rapid_cut = std::max(stats.max_rapid_cut, removed);
    }
  }
  return stats;
}

}  // namespace subfab
