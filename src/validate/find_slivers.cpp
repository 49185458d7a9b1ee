// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/validate/find_slivers.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;

//! A mesh's vertices in the block's frame: (v.p, w.p) on the plane across
//! the thin axis u, and h = u.p along it (each vertex projected once, so
//! shared edges project identically).
struct Projected {
  std::vector<Point2> plane;
  std::vector<double> height;
};

Projected project(const Mesh& m, const Vec3& u, const Vec3& v, const Vec3& w) {
  Projected p;
  p.plane.reserve(m.num_vertices());
  p.height.reserve(m.num_vertices());
  for (const Vec3& x : m.vertices) {
    p.plane.emplace_back(v.dot(x), w.dot(x));
    p.height.push_back(u.dot(x));
  }
  return p;
}

//! The grid of lines across a footprint [s0, s1] x [t0, t1]: line (i, j)
//! passes at (s(i), t(j)), at irrational offsets inside the cells.
struct LineGrid {
  double s0 = 0, ds = 0, t0 = 0, dt = 0;
  int n = 1;
  static constexpr double kOffsetS = 0.41421356237309515;  // sqrt(2) - 1
  static constexpr double kOffsetT = 0.7320508075688772;   // sqrt(3) - 1
  double s(int i) const { return s0 + (i + kOffsetS) * ds; }
  double t(int j) const { return t0 + (j + kOffsetT) * dt; }
  //! Lines i with lo <= s(i) <= hi: [first, last] (empty when first > last).
  std::pair<int, int> s_range(double lo, double hi) const { return range(lo, hi, s0, ds, kOffsetS); }
  std::pair<int, int> t_range(double lo, double hi) const { return range(lo, hi, t0, dt, kOffsetT); }

 private:
  std::pair<int, int> range(double lo, double hi, double origin, double step, double offset) const {
    if (step <= 0) return {0, n - 1};
    const int a = std::max(0, static_cast<int>(std::floor((lo - origin) / step - offset)) - 1);
    const int b = std::min(n - 1, static_cast<int>(std::ceil((hi - origin) / step - offset)) + 1);
    return {a, b};
  }
};

//! The crossings of every grid line with a closed mesh's faces: per line,
//! the sorted heights, or nullopt when the line is degenerate (through a
//! vertex or an edge) or crosses an odd number of times.
std::vector<std::optional<std::vector<double>>> crossings(const Mesh& m, const Projected& p, const LineGrid& grid) {
  const int n = grid.n;
  std::vector<std::optional<std::vector<double>>> lines(static_cast<std::size_t>(n * n), std::vector<double>{});
  for (const Triangle& f : m.faces) {
    const Point2& a = p.plane[static_cast<std::size_t>(f[0])];
    const Point2& b = p.plane[static_cast<std::size_t>(f[1])];
    const Point2& c = p.plane[static_cast<std::size_t>(f[2])];
    // A face parallel to the lines is crossed only by lines in its plane,
    // which then pass through an edge of a neighbouring face (dropped there).
    if (CGAL::orientation(a, b, c) == CGAL::COLLINEAR) continue;
    const auto [i0, i1] = grid.s_range(std::min({a.x(), b.x(), c.x()}), std::max({a.x(), b.x(), c.x()}));
    const auto [j0, j1] = grid.t_range(std::min({a.y(), b.y(), c.y()}), std::max({a.y(), b.y(), c.y()}));
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j) {
        auto& line = lines[static_cast<std::size_t>(i * n + j)];
        if (!line) continue;
        const Point2 q(grid.s(i), grid.t(j));
        const CGAL::Orientation o[3] = {CGAL::orientation(a, b, q), CGAL::orientation(b, c, q),
                                        CGAL::orientation(c, a, q)};
        bool pos = false, neg = false, zero = false;
        for (const CGAL::Orientation x : o) (x == CGAL::POSITIVE ? pos : x == CGAL::NEGATIVE ? neg : zero) = true;
        if (pos && neg) continue;  // q outside the triangle
        if (zero) {                // q on an edge or a vertex (or the triangle is flat and q on its line)
          line.reset();
          continue;
        }
        // Strictly inside: the height by barycentric interpolation.
        const auto area = [](const Point2& x, const Point2& y, const Point2& z) {
          return (y.x() - x.x()) * (z.y() - x.y()) - (y.y() - x.y()) * (z.x() - x.x());
        };
        const double la = area(q, b, c), lb = area(a, q, c), lc = area(a, b, q), sum = la + lb + lc;
        if (!(sum != 0.0)) {
          line.reset();
          continue;
        }
        line->push_back((la * p.height[static_cast<std::size_t>(f[0])] + lb * p.height[static_cast<std::size_t>(f[1])] +
                         lc * p.height[static_cast<std::size_t>(f[2])]) /
                        sum);
      }
  }
  for (auto& line : lines)
    if (line) {
      if (line->size() % 2 != 0)
        line.reset();
      else
        std::sort(line->begin(), line->end());
    }
  return lines;
}

//! The faces of `m` whose projected bounding box meets the footprint.
Mesh faces_over(const Mesh& m, const Projected& p, double s0, double s1, double t0, double t1) {
  Mesh out;
  out.vertices = m.vertices;
  for (const Triangle& f : m.faces) {
    double lo_s = std::numeric_limits<double>::infinity(), hi_s = -lo_s, lo_t = lo_s, hi_t = -lo_s;
    for (int k = 0; k < 3; ++k) {
      const Point2& x = p.plane[static_cast<std::size_t>(f[static_cast<std::size_t>(k)])];
      lo_s = std::min(lo_s, x.x());
      hi_s = std::max(hi_s, x.x());
      lo_t = std::min(lo_t, x.y());
      hi_t = std::max(hi_t, x.y());
    }
    if (hi_s >= s0 && lo_s <= s1 && hi_t >= t0 && lo_t <= t1) out.faces.push_back(f);
  }
  return out;
}

//! Casts the lines of one thin block: its segments and the input's.
void measure_lines(const Mesh& input, const SliverBlock& block, int num_lines, SliverMeasure& r) {
  const Eigen::Matrix3d& frame = block.frame;
  const int k = r.thickness.thinnest_row;
  const Vec3 u = frame.row(k).transpose(), v = frame.row((k + 1) % 3).transpose(),
             w = frame.row((k + 2) % 3).transpose();
  const Projected pb = project(*block.mesh, u, v, w);
  double s0 = std::numeric_limits<double>::infinity(), s1 = -s0, t0 = s0, t1 = -s0;
  for (const Point2& x : pb.plane) {
    s0 = std::min(s0, x.x());
    s1 = std::max(s1, x.x());
    t0 = std::min(t0, x.y());
    t1 = std::max(t1, x.y());
  }
  const Projected pi = project(input, u, v, w);
  const Mesh near = faces_over(input, pi, s0, s1, t0, t1);
  for (const int n : {num_lines, 4 * num_lines}) {
    LineGrid grid{.s0 = s0, .ds = (s1 - s0) / n, .t0 = t0, .dt = (t1 - t0) / n, .n = n};
    const auto in_block = crossings(*block.mesh, pb, grid);
    const auto in_model = crossings(near, pi, grid);
    double block_sum = 0.0, model_sum = 0.0;
    std::size_t count = 0;
    for (std::size_t l = 0; l < in_block.size(); ++l) {
      if (!in_block[l] || !in_model[l]) continue;
      const std::vector<double>& b = *in_block[l];
      const std::vector<double>& m = *in_model[l];
      for (std::size_t q = 0; q + 1 < b.size(); q += 2) {
        const double mid = 0.5 * (b[q] + b[q + 1]);
        double model = 0.0;  // no input segment holds it: the block sticks out there
        for (std::size_t e = 0; e + 1 < m.size(); e += 2)
          if (m[e] <= mid && mid <= m[e + 1]) model = m[e + 1] - m[e];
        block_sum += b[q + 1] - b[q];
        model_sum += model;
        ++count;
      }
    }
    if (count == 0) continue;
    r.num_chords = count;
    r.block_chord = block_sum / static_cast<double>(count);
    r.model_chord = model_sum / static_cast<double>(count);
    return;
  }
}

}  // namespace

std::vector<SliverMeasure> find_slivers(const Mesh& input, const std::vector<SliverBlock>& blocks,
                                        const SliverOptions& options) {
  if (!(options.min_thickness > 0))
    throw InvalidArgumentError("find_slivers: min_thickness must be > 0 (model units)");
  if (options.num_lines < 1) throw InvalidArgumentError("find_slivers: num_lines must be >= 1");
  std::vector<SliverMeasure> out(blocks.size());
  parallel_for(0, blocks.size(), [&](std::size_t i) {
    SliverMeasure& r = out[i];
    r.thickness = block_thickness(*blocks[i].mesh, blocks[i].frame);
    if (r.thickness.thickness >= options.min_thickness) return;
    r.measured = true;
    measure_lines(input, blocks[i], options.num_lines, r);
    r.sliver = r.num_chords == 0 || r.model_chord > options.min_thickness;
  });
  return out;
}

double sliver_threshold(double floor, double tolerance, double max_height) {
  return std::max(floor, std::min(tolerance, max_height / 4));
}

}  // namespace subfab
