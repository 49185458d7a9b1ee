// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mill/rough_toolpath.h"

#include <algorithm>
#include <cmath>

#include "mill/path_builder.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

using detail::ceil_mm;
using detail::round_mm;
using detail::spaced;

struct Samples {
  std::vector<double> xs, ys;
  std::vector<double> height;  // [j * xs.size() + i]: lowest safe tool height at (xs[i], ys[j])
  double at(std::size_t j, std::size_t i) const { return height[j * xs.size() + i]; }
};

}  // namespace

Toolpath rough_toolpath(const TriangleGrid& grid, const Stock& stock, const RoughingOptions& o) {
  if (o.tool.shape != ToolShape::Flat) throw InvalidArgumentError("roughing needs a flat end mill (flat:D)");
  if (!(o.stepdown > 0.0)) throw InvalidArgumentError("--stepdown must be positive (mm)");
  if (!(o.allowance >= 0.0)) throw InvalidArgumentError("--allowance must be zero or positive (mm)");
  if (!(o.stepover > 0.0 && o.stepover <= 1.0) || !(o.step > 0.0))
    throw InvalidArgumentError("roughing stepover must be in (0, 1] and the step positive");
  Toolpath path;
  path.tool = o.tool;
  path.role = "roughing";
  path.safe_z = ceil_mm(stock.z + o.safe_height);

  Samples s;
  s.xs = spaced(stock.x, o.step);
  s.ys = spaced(stock.y, o.stepover * o.tool.diameter);
  const double h = s.xs.size() > 1 ? s.xs[1] - s.xs[0] : 0.0;
  const Tool inflated{ToolShape::Flat, 2.0 * (o.tool.radius() + o.allowance + 0.5 * h + 0.001)};
  s.height.resize(s.xs.size() * s.ys.size());
  parallel_for(0, s.ys.size(), [&](std::size_t j) {
    for (std::size_t i = 0; i < s.xs.size(); ++i)
      s.height[j * s.xs.size() + i] = ceil_mm(drop_cutter(grid, inflated, s.xs[i], s.ys[j]) + o.allowance);
  });
  const double lowest = *std::min_element(s.height.begin(), s.height.end());
  std::vector<double> levels;
  for (int k = 1;; ++k) {
    const double z = round_mm(stock.z - k * o.stepdown);
    if (z <= lowest) break;
    levels.push_back(z);
  }
  if (lowest < stock.z) levels.push_back(lowest);

  const double reach = o.tool.radius() + h + 0.001;
  const double line_gap = s.ys.size() > 1 ? s.ys[1] - s.ys[0] : 0.0;
  // Highest material the tool may meet moving anywhere in the xy box
  // [x0, x1] x [y0, y1] after level `prev`: every point of its disk lies in
  // the disk of a sample within the box grown by the reach, where the
  // material is at most max(prev, sample height).
  auto material_bound = [&](double x0, double y0, double x1, double y1, double prev) {
    double top = prev;
    for (std::size_t j = 0; j < s.ys.size(); ++j) {
      if (s.ys[j] < y0 - reach - line_gap || s.ys[j] > y1 + reach + line_gap) continue;
      for (std::size_t i = 0; i < s.xs.size(); ++i)
        if (s.xs[i] >= x0 - reach && s.xs[i] <= x1 + reach) top = std::max(top, s.at(j, i));
    }
    return std::min(top, stock.z);
  };

  detail::PathBuilder out(Vec3(0.0, 0.0, path.safe_z), 1e-4);
  const std::size_t n = s.xs.size();
  const std::size_t merge_gap = static_cast<std::size_t>(std::ceil(2.0 * o.tool.diameter / std::max(h, 1e-9)));
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const double level = levels[k], prev = k == 0 ? stock.z : levels[k - 1];
    for (std::size_t j = 0; j < s.ys.size(); ++j) {
      // Runs of samples with material above them at this level (grown by one
      // sample each side, gaps shorter than two diameters bridged).
      std::vector<std::pair<std::size_t, std::size_t>> runs;
      for (std::size_t i = 0; i < n; ++i) {
        if (!(s.at(j, i) < prev)) continue;
        const std::size_t a = i > 0 ? i - 1 : 0, b = std::min(i + 1, n - 1);
        if (!runs.empty() && a <= runs.back().second + merge_gap)
          runs.back().second = b;
        else
          runs.push_back({a, b});
      }
      const bool reverse = j % 2 == 1;
      if (reverse) std::reverse(runs.begin(), runs.end());
      for (auto [a, b] : runs) {
        if (reverse) std::swap(a, b);
        const Vec3 here = out.position();
        const double x0 = s.xs[a], y = s.ys[j];
        const double start_z = std::max(level, s.at(j, a));
        // Link: up, across, down (rapid), then plunge into the material.
        const double over = ceil_mm(material_bound(std::min(here.x(), x0), std::min(here.y(), y),
                                                   std::max(here.x(), x0), std::max(here.y(), y), prev) +
                                    o.clearance);
        const double link_z = std::min(path.safe_z, std::max(over, here.z()));
        out.add(MoveKind::Rapid, Vec3(here.x(), here.y(), link_z));
        out.add(MoveKind::Rapid, Vec3(x0, y, link_z));
        const double entry = std::min(link_z, ceil_mm(std::max(prev, s.at(j, a)) + o.clearance));
        out.add(MoveKind::Rapid, Vec3(x0, y, entry));
        out.add(MoveKind::Plunge, Vec3(x0, y, start_z));
        // Along the run, in vertical steps: up before moving, down after.
        const int dir = a <= b ? 1 : -1;
        for (std::size_t i = a; i != b;) {
          const std::size_t next = static_cast<std::size_t>(static_cast<long>(i) + dir);
          const double za = std::max(level, s.at(j, i)), zb = std::max(level, s.at(j, next));
          if (zb > za) out.add(MoveKind::Cut, Vec3(s.xs[i], y, zb));
          out.add(MoveKind::Cut, Vec3(s.xs[next], y, std::max(za, zb)));
          if (zb < za) out.add(MoveKind::Plunge, Vec3(s.xs[next], y, zb));
          i = next;
        }
      }
    }
  }
  const Vec3 end = out.position();
  out.add(MoveKind::Rapid, Vec3(end.x(), end.y(), path.safe_z));
  path.moves = out.take();
  return path;
}

}  // namespace subfab
