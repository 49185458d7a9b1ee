// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mill/finish_toolpath.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mill/path_builder.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

using detail::ceil_mm;
using detail::round_mm;
using detail::spaced;

struct Refiner {
  const TriangleGrid& grid;
  const Tool& tool;
  double tolerance;

  double height(double x, double y) const { return ceil_mm(drop_cutter(grid, tool, x, y)); }

  //! The point on the 0.001 mm grid halfway between a and b, at its height.
  Vec3 midpoint(const Vec3& a, const Vec3& b) const {
    const double mx = round_mm(0.5 * (a.x() + b.x())), my = round_mm(0.5 * (a.y() + b.y()));
    return Vec3(mx, my, height(mx, my));
  }

  //! How far p's height is from the chord a-b at p's xy.
  static double off_chord(const Vec3& a, const Vec3& b, const Vec3& p) {
    const Eigen::Vector2d u = b.head<2>() - a.head<2>();
    const double len2 = u.squaredNorm();
    const double t = len2 > 0 ? (p.head<2>() - a.head<2>()).dot(u) / len2 : 0.5;
    return std::abs(p.z() - (a.z() + t * (b.z() - a.z())));
  }

  static bool same_xy(const Vec3& p, const Vec3& q) { return p.x() == q.x() && p.y() == q.y(); }

  //! Appends the points after `a` up to and including `b` (both on the
  //! drop-cutter surface; m the surface point halfway between them) so that
  //! the polyline stays within tolerance of it. The segment is accepted when
  //! the surface at its midpoint and at its quarter points is within
  //! tolerance of the chord: a midpoint alone can sit on the chord of an
  //! S-shaped stretch (a crease then a ridge) whose ridge the chord cuts.
  //! The quarter points are the halves' midpoints, so nothing is computed
  //! twice.
  void refine(const Vec3& a, const Vec3& m, const Vec3& b, std::vector<Vec3>& out, int depth) const {
    const bool splittable = depth < 40 && !same_xy(m, a) && !same_xy(m, b);
    if (splittable) {
      const Vec3 q1 = midpoint(a, m), q3 = midpoint(m, b);
      if (off_chord(a, b, m) <= tolerance && off_chord(a, b, q1) <= tolerance && off_chord(a, b, q3) <= tolerance) {
        out.push_back(b);
        return;
      }
      refine(a, q1, m, out, depth + 1);
      refine(m, q3, b, out, depth + 1);
      return;
    }
    // Too short to split: a vertical step at the higher end.
    const double top = std::max({a.z(), b.z(), m.z()});
    if (top > a.z()) out.push_back(Vec3(a.x(), a.y(), top));
    out.push_back(Vec3(b.x(), b.y(), top));
    if (top > b.z()) out.push_back(b);
  }

  //! Points from (x0, y0) to (x1, y1), the first included.
  void sweep(double x0, double y0, double x1, double y1, double step, std::vector<Vec3>& out) const {
    const double len = std::hypot(x1 - x0, y1 - y0);
    const int n = std::max(1, static_cast<int>(std::ceil(len / step - 1e-9)));
    Vec3 prev(x0, y0, height(x0, y0));
    out.push_back(prev);
    for (int i = 1; i <= n; ++i) {
      const double x = i == n ? x1 : round_mm(x0 + (x1 - x0) * i / n);
      const double y = i == n ? y1 : round_mm(y0 + (y1 - y0) * i / n);
      const Vec3 next(x, y, height(x, y));
      refine(prev, midpoint(prev, next), next, out, 0);
      prev = next;
    }
  }
};

//! Runs [first, last] of sample indices along one cross line, in +y order.
using Runs = std::vector<std::pair<std::size_t, std::size_t>>;

//! The cross pass's runs: on line i (x = xs[i]) the samples where the
//! drop-cutter surface `cl` ([i * ny + k]) rises towards +-y steeper than
//! `slope` and steeper than towards +-x, grown by `grow` samples each side,
//! gaps of at most `bridge` samples bridged.
std::vector<Runs> steep_runs(const std::vector<double>& xs, const std::vector<double>& ys, const std::vector<double>& cl,
                             double slope, std::size_t grow, std::size_t bridge) {
  const std::size_t nx = xs.size(), ny = ys.size();
  auto at = [&](std::size_t i, std::size_t k) { return cl[i * ny + k]; };
  std::vector<Runs> runs(nx);
  if (ny < 2) return runs;
  for (std::size_t i = 0; i < nx; ++i) {
    std::vector<char> steep(ny, 0);
    for (std::size_t k = 0; k < ny; ++k) {
      const std::size_t k0 = k > 0 ? k - 1 : k, k1 = std::min(k + 1, ny - 1);
      const double sy = std::abs(at(i, k1) - at(i, k0)) / (ys[k1] - ys[k0]);
      double sx = 0.0;
      if (nx > 1) {
        const std::size_t i0 = i > 0 ? i - 1 : i, i1 = std::min(i + 1, nx - 1);
        sx = std::abs(at(i1, k) - at(i0, k)) / (xs[i1] - xs[i0]);
      }
      steep[k] = sy >= slope && sy > sx;
    }
    for (std::size_t k = 0; k < ny; ++k) {
      if (!steep[k]) continue;
      const std::size_t a = k > grow ? k - grow : 0, b = std::min(k + grow, ny - 1);
      if (!runs[i].empty() && a <= runs[i].back().second + bridge)
        runs[i].back().second = std::max(runs[i].back().second, b);
      else
        runs[i].push_back({a, b});
    }
  }
  return runs;
}

//! Appends the cross pass (lines along y through the steep runs) to `out`,
//! each run entered from a height above the material the x raster can have
//! left (see finish_toolpath.h).
void add_cross_pass(const TriangleGrid& grid, const Stock& stock, const FinishingOptions& o, const Refiner& refiner,
                    double safe_z, detail::PathBuilder& out) {
  const double spacing = o.stepover * o.tool.diameter, r = o.tool.radius();
  const std::vector<double> xs = spaced(stock.x, spacing), ys = spaced(stock.y, o.step);
  const std::size_t ny = ys.size();
  std::vector<double> cl(xs.size() * ny);
  parallel_for(0, xs.size(), [&](std::size_t i) {
    for (std::size_t k = 0; k < ny; ++k) cl[i * ny + k] = refiner.height(xs[i], ys[k]);
  });
  const double h = ny > 1 ? ys[1] - ys[0] : o.step;
  const std::vector<Runs> runs = steep_runs(xs, ys, cl, std::tan(o.cross_angle * std::numbers::pi / 180.0),
                                            static_cast<std::size_t>(std::ceil(r / h)),
                                            static_cast<std::size_t>(std::ceil(o.tool.diameter / h)));
  // The runs, swept in parallel per line (alternate lines towards -y), in order.
  std::vector<std::vector<std::vector<Vec3>>> sweeps(xs.size());
  parallel_for(0, xs.size(), [&](std::size_t i) {
    for (auto [a, b] : runs[i]) {
      if (i % 2 == 1) std::swap(a, b);
      sweeps[i].emplace_back();
      refiner.sweep(xs[i], ys[a], xs[i], ys[b], o.step, sweeps[i].back());
    }
    if (i % 2 == 1) std::reverse(sweeps[i].begin(), sweeps[i].end());
  });
  // Material bound: after the x raster, the material at p is at most the
  // tool's height at the nearest raster line (within spacing/2 of p, within
  // `tolerance` of the drop-cutter height there, which is at most the
  // highest mesh point within R) plus the ball's profile at spacing/2. So
  // under a tool centred at c it is at most the highest mesh point within
  // 2R + spacing/2 of c (a flat drop-cutter of that radius) plus that.
  const Tool wide{ToolShape::Flat, 2.0 * (2.0 * r + 0.5 * spacing + 0.5 + 0.001)};  // + 0.5: half the link's sampling
  const double lift = o.tolerance + tool_profile(o.tool, std::min(r, 0.5 * spacing)) + 1.0;  // 1 mm clearance
  auto bound = [&](double x, double y) { return ceil_mm(drop_cutter(grid, wide, x, y) + lift); };
  for (const auto& line : sweeps)
    for (const auto& pts : line) {
      const Vec3 from = out.position(), to = pts.front();
      const double len = (to - from).head<2>().norm();
      if (len <= 3.0 * o.tool.diameter) {
        // Near: along the drop-cutter surface, like any finishing cut
        // (cheaper than a lift and a plunge at the plunge feed).
        std::vector<Vec3> link;
        refiner.sweep(from.x(), from.y(), to.x(), to.y(), o.step, link);
        for (std::size_t k = 1; k < link.size(); ++k) out.add(MoveKind::Cut, link[k]);
        for (const Vec3& p : pts) out.add(MoveKind::Cut, p);
        continue;
      }
      const int n = std::max(1, static_cast<int>(std::ceil(len / 1.0)));
      double over = std::max(from.z(), to.z());
      for (int k = 0; k <= n; ++k) {
        const double t = static_cast<double>(k) / n;
        over = std::max(over, bound(from.x() + t * (to.x() - from.x()), from.y() + t * (to.y() - from.y())));
      }
      over = std::min(over, safe_z);
      out.add(MoveKind::Rapid, Vec3(from.x(), from.y(), over));
      out.add(MoveKind::Rapid, Vec3(to.x(), to.y(), over));
      out.add(MoveKind::Rapid, Vec3(to.x(), to.y(), std::clamp(bound(to.x(), to.y()), to.z(), over)));
      out.add(MoveKind::Plunge, to);
      for (const Vec3& p : pts) out.add(MoveKind::Cut, p);
    }
}

}  // namespace

Toolpath finish_toolpath(const TriangleGrid& grid, const Stock& stock, const FinishingOptions& o) {
  if (!(o.stepover > 0.0 && o.stepover <= 1.0))
    throw InvalidArgumentError("--stepover must be a fraction of the tool diameter in (0, 1]");
  if (!(o.step > 0.0) || !(o.tolerance > 0.0)) throw InvalidArgumentError("finishing step and tolerance must be positive");
  if (!(o.cross_angle > 0.0)) throw InvalidArgumentError("--cross-angle must be positive (degrees; 90 or more: no cross pass)");
  Toolpath path;
  path.tool = o.tool;
  path.role = "finishing";
  path.safe_z = ceil_mm(stock.z + o.safe_height);

  const double spacing = o.stepover * o.tool.diameter;
  const std::vector<double> ys = spaced(stock.y, spacing);
  const double x_end = round_mm(stock.x);
  const Refiner refiner{grid, o.tool, o.tolerance};
  // Line j (and its link to line j + 1), computed in parallel, joined in order.
  std::vector<std::vector<Vec3>> pieces(ys.size());
  parallel_for(0, ys.size(), [&](std::size_t j) {
    const bool forward = j % 2 == 0;
    const double xa = forward ? 0.0 : x_end, xb = forward ? x_end : 0.0;
    std::vector<Vec3>& pts = pieces[j];
    refiner.sweep(xa, ys[j], xb, ys[j], o.step, pts);
    if (j + 1 < ys.size()) {
      std::vector<Vec3> link;
      refiner.sweep(xb, ys[j], xb, ys[j + 1], o.step, link);
      pts.insert(pts.end(), link.begin() + 1, link.end() - 1);  // link's ends are the lines' ends
    }
  });

  detail::PathBuilder out(Vec3(0.0, 0.0, path.safe_z), 1e-4);
  const Vec3& first = pieces.front().front();
  out.add(MoveKind::Rapid, Vec3(first.x(), first.y(), path.safe_z));
  out.add(MoveKind::Rapid, Vec3(first.x(), first.y(), std::min(path.safe_z, ceil_mm(stock.z + 1.0))));
  out.add(MoveKind::Plunge, first);
  for (const auto& piece : pieces)
    for (const Vec3& p : piece) out.add(MoveKind::Cut, p);
  if (o.cross_angle < 90.0) add_cross_pass(grid, stock, o, refiner, path.safe_z, out);
  const Vec3 end = out.position();
  out.add(MoveKind::Rapid, Vec3(end.x(), end.y(), path.safe_z));
  path.moves = out.take();
  return path;
}

}  // namespace subfab
