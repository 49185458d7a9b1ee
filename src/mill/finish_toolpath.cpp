// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mill/finish_toolpath.h"

#include <algorithm>
#include <cmath>

#include "mill/path_builder.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

using detail::ceil_mm;
using detail::round_mm;

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

}  // namespace

Toolpath finish_toolpath(const TriangleGrid& grid, const Stock& stock, const FinishingOptions& o) {
  if (!(o.stepover > 0.0 && o.stepover <= 1.0))
    throw InvalidArgumentError("--stepover must be a fraction of the tool diameter in (0, 1]");
  if (!(o.step > 0.0) || !(o.tolerance > 0.0)) throw InvalidArgumentError("finishing step and tolerance must be positive");
  Toolpath path;
  path.tool = o.tool;
  path.role = "finishing";
  path.safe_z = ceil_mm(stock.z + o.safe_height);

  const double spacing = o.stepover * o.tool.diameter;
  const int num_lines = std::max(1, static_cast<int>(std::ceil(stock.y / spacing - 1e-9)) + 1);
  std::vector<double> ys(static_cast<std::size_t>(num_lines));
  for (int j = 0; j < num_lines; ++j)
    ys[static_cast<std::size_t>(j)] = num_lines == 1 ? 0.0 : round_mm(stock.y * j / (num_lines - 1));
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
  const Vec3 end = out.position();
  out.add(MoveKind::Rapid, Vec3(end.x(), end.y(), path.safe_z));
  path.moves = out.take();
  return path;
}

}  // namespace subfab
