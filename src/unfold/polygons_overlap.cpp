// SPDX-License-Identifier: GPL-3.0-or-later
#include "unfold/polygons_overlap.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Gmpq.h>

#include <algorithm>

namespace subfab::unfold_detail {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P = K::Point_2;
using Vec2 = Eigen::Vector2d;

int orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return static_cast<int>(CGAL::orientation(P(a.x(), a.y()), P(b.x(), b.y()), P(c.x(), c.y())));
}

// c on the closed segment ab, given that the three are collinear.
bool between(const Vec2& a, const Vec2& b, const Vec2& c) {
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= c.y() &&
         c.y() <= std::max(a.y(), b.y());
}

enum class Where { Outside, Boundary, Inside };

Where locate(const Polygon2& poly, const Vec2& q) {
  if (q.x() < poly.lo.x() || q.x() > poly.hi.x() || q.y() < poly.lo.y() || q.y() > poly.hi.y())
    return Where::Outside;
  bool inside = false;
  for (const auto& loop : poly.loops) {
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2& a = loop[i];
      const Vec2& b = loop[(i + 1) % n];
      const int o = orient(a, b, q);
      if (o == 0 && between(a, b, q)) return Where::Boundary;
      if ((a.y() > q.y()) != (b.y() > q.y())) {
        const int side = (b.y() > a.y()) ? o : -o;
        if (side > 0) inside = !inside;
      }
    }
  }
  return inside ? Where::Inside : Where::Outside;
}

// Exact location of the midpoint of s0 s1 (rational arithmetic).
Where locate_midpoint(const Polygon2& poly, const Vec2& s0, const Vec2& s1) {
  using Q = CGAL::Gmpq;
  const Q qx = (Q(s0.x()) + Q(s1.x())) / Q(2), qy = (Q(s0.y()) + Q(s1.y())) / Q(2);
  bool inside = false;
  for (const auto& loop : poly.loops) {
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Q ax(loop[i].x()), ay(loop[i].y());
      const Q bx(loop[(i + 1) % n].x()), by(loop[(i + 1) % n].y());
      const int o = CGAL::sign((bx - ax) * (qy - ay) - (by - ay) * (qx - ax));
      if (o == 0 && std::min(ax, bx) <= qx && qx <= std::max(ax, bx) && std::min(ay, by) <= qy &&
          qy <= std::max(ay, by))
        return Where::Boundary;
      if ((ay > qy) != (by > qy)) {
        const int side = (by > ay) ? o : -o;
        if (side > 0) inside = !inside;
      }
    }
  }
  return inside ? Where::Inside : Where::Outside;
}

bool proper_crossing(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const int o1 = orient(a, b, c), o2 = orient(a, b, d);
  if (o1 * o2 >= 0) return false;
  const int o3 = orient(c, d, a), o4 = orient(c, d, b);
  return o3 * o4 < 0;
}

// One direction of the test: does some edge of `a` have the interior of `b`
// on its left somewhere? (a's vertices strictly inside b were tested before.)
bool edges_enter(const Polygon2& a, const Polygon2& b) {
  std::vector<std::pair<const Vec2*, const Vec2*>> b_edges;
  for (const auto& loop : b.loops)
    for (std::size_t i = 0; i < loop.size(); ++i) b_edges.emplace_back(&loop[i], &loop[(i + 1) % loop.size()]);
  for (const auto& loop : a.loops)
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec2& s = loop[i];
      const Vec2& t = loop[(i + 1) % loop.size()];
      const Vec2 lo = s.cwiseMin(t), hi = s.cwiseMax(t);
      if ((hi.array() < b.lo.array()).any() || (lo.array() > b.hi.array()).any()) continue;
      const Where ws = locate(b, s), wt = locate(b, t);
      if (ws == Where::Outside || wt == Where::Outside) {
        // Only the part between split points matters; an outside endpoint
        // only settles its own piece, so fall through to the split below.
      }
      // Split points: vertices of b strictly inside segment st.
      std::vector<std::pair<double, Vec2>> splits;
      const Vec2 dir = t - s;
      for (const auto& [c, d] : b_edges) {
        (void)d;
        if (*c == s || *c == t) continue;
        if (orient(s, t, *c) == 0 && between(s, t, *c)) splits.emplace_back(dir.dot(*c - s), *c);
      }
      std::sort(splits.begin(), splits.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      std::vector<Vec2> pts{s};
      for (const auto& sp : splits) pts.push_back(sp.second);
      pts.push_back(t);
      for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
        const Vec2& p0 = pts[k];
        const Vec2& p1 = pts[k + 1];
        if (p0 == p1) continue;
        const Where w0 = (k == 0) ? ws : Where::Boundary;
        const Where w1 = (k + 2 == pts.size()) ? wt : Where::Boundary;
        if (w0 == Where::Inside || w1 == Where::Inside) return true;
        if (w0 == Where::Outside || w1 == Where::Outside) continue;  // piece lies outside
        // Both ends on b's boundary: along an edge of b, or inside/outside.
        bool along = false;
        for (const auto& [c, d] : b_edges) {
          if (orient(*c, *d, p0) == 0 && orient(*c, *d, p1) == 0 && between(*c, *d, p0) && between(*c, *d, p1)) {
            along = true;
            if ((p1 - p0).dot(*d - *c) > 0) return true;  // same direction: interiors on the same side
            break;
          }
        }
        if (along) continue;
        if (locate_midpoint(b, p0, p1) == Where::Inside) return true;
      }
    }
  return false;
}

}  // namespace

void update_box(Polygon2& p) {
  p.lo = Vec2::Constant(1e300);
  p.hi = Vec2::Constant(-1e300);
  for (const auto& loop : p.loops)
    for (const auto& v : loop) {
      p.lo = p.lo.cwiseMin(v);
      p.hi = p.hi.cwiseMax(v);
    }
}

bool interiors_overlap(const Polygon2& a, const Polygon2& b) {
  if ((a.hi.array() < b.lo.array()).any() || (b.hi.array() < a.lo.array()).any()) return false;
  for (const auto& la : a.loops)
    for (std::size_t i = 0; i < la.size(); ++i) {
      const Vec2& p = la[i];
      const Vec2& q = la[(i + 1) % la.size()];
      for (const auto& lb : b.loops)
        for (std::size_t j = 0; j < lb.size(); ++j)
          if (proper_crossing(p, q, lb[j], lb[(j + 1) % lb.size()])) return true;
    }
  for (const auto& la : a.loops)
    for (const auto& v : la)
      if (locate(b, v) == Where::Inside) return true;
  for (const auto& lb : b.loops)
    for (const auto& v : lb)
      if (locate(a, v) == Where::Inside) return true;
  return edges_enter(a, b) || edges_enter(b, a);
}

}  // namespace subfab::unfold_detail
