// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_no_intersections.cpp
//! Exact intersection checks of facet deletion (thesis Section 3.3.2): each
//! facet of an ExactPolyMesh simple, and no two facets meeting except along
//! shared edges and at shared vertices. 2-D predicates on a facet's plane
//! projected along its normal's first non-zero axis; every decision exact.
#include "unfold/check_no_intersections.h"

#include <algorithm>

namespace subfab::unfold_detail {

namespace {

int orient(const P2& a, const P2& b, const P2& c) {
  return CGAL::sign((b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u));
}

// c on the closed segment ab, given orient(a, b, c) == 0.
bool between(const P2& a, const P2& b, const P2& c) {
  return std::min(a.u, b.u) <= c.u && c.u <= std::max(a.u, b.u) && std::min(a.v, b.v) <= c.v &&
         c.v <= std::max(a.v, b.v);
}

// Closed segments ab and cd intersect.
bool segments_meet(const P2& a, const P2& b, const P2& c, const P2& d) {
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  if (o1 == 0 && between(a, b, c)) return true;
  if (o2 == 0 && between(a, b, d)) return true;
  if (o3 == 0 && between(c, d, a)) return true;
  if (o4 == 0 && between(c, d, b)) return true;
  return false;
}

Where locate_in_loops(const ExactPolyMesh& mesh, const std::vector<std::vector<int>>& loops, int k,
                      const QVec& p) {
  const P2 q = project(p, k);
  bool inside = false;
  for (const auto& loop : loops) {
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const P2 a = project(mesh.points[loop[i]], k);
      const P2 b = project(mesh.points[loop[(i + 1) % n]], k);
      const int o = orient(a, b, q);
      if (o == 0 && between(a, b, q)) return Where::Boundary;
      // Crossing number along +u ray from q (half-open rule on v).
      if ((a.v > q.v) != (b.v > q.v)) {
        // u of the crossing > q.u  <=>  orientation sign test
        const int side = (b.v > a.v) ? o : -o;
        if (side > 0) inside = !inside;
      }
    }
  }
  return inside ? Where::Inside : Where::Outside;
}

struct Box {
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  bool overlaps(const Box& o, double eps) const {
    return (lo.array() <= o.hi.array() + eps).all() && (o.lo.array() <= hi.array() + eps).all();
  }
};

Box facet_box(const ExactPolyMesh& mesh, const QFacet& f) {
  Box b;
  for (const auto& loop : f.loops)
    for (int v : loop) {
      b.lo = b.lo.cwiseMin(mesh.approx[v]);
      b.hi = b.hi.cwiseMax(mesh.approx[v]);
    }
  return b;
}

double box_eps(const ExactPolyMesh& mesh) {
  double scale = 1;
  for (const auto& p : mesh.approx) scale = std::max(scale, p.cwiseAbs().maxCoeff());
  return 1e-9 * scale + (mesh.frame.step > 0 ? 1e-9 * mesh.frame.step : 0.0);
}

}  // namespace

Where locate_in_facet(const ExactPolyMesh& mesh, const QFacet& facet, const QVec& p) {
  return locate_in_loops(mesh, facet.loops, drop_axis(facet), p);
}

std::string check_facet_simple(const ExactPolyMesh& mesh, int f) {
  const QFacet& facet = mesh.facets[f];
  const std::string name = "facet " + std::to_string(f);
  const int k = drop_axis(facet);
  const QVec n = to_qvec(facet.normal);
  std::vector<int> all;
  for (const auto& loop : facet.loops)
    for (int v : loop) {
      if (dot(n, mesh.points[v]) != facet.offset) return name + " is not planar";
      all.push_back(v);
    }
  for (std::size_t l = 0; l < facet.loops.size(); ++l) {
    const Q area = loop_area2(mesh, facet, facet.loops[l]);
    if (l == 0 && !(area > 0)) return name + " has a non-positive outer loop";
    if (l > 0 && !(area < 0)) return name + " has a hole loop with the wrong orientation";
    if (l > 0) {
      // a hole may touch the outer loop at a vertex (a pinch): test a vertex that does not
      for (int v : facet.loops[l]) {
        const Where w = locate_in_loops(mesh, {facet.loops[0]}, k, mesh.points[v]);
        if (w == Where::Boundary) continue;
        if (w == Where::Outside) return name + " has a hole outside its outer loop";
        break;
      }
    }
  }
  struct Seg {
    int a, b;
    Vec3 lo, hi;
  };
  std::vector<Seg> segs;
  for (const auto& loop : facet.loops)
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i], b = loop[(i + 1) % loop.size()];
      segs.push_back({a, b, mesh.approx[a].cwiseMin(mesh.approx[b]), mesh.approx[a].cwiseMax(mesh.approx[b])});
    }
  const double eps = box_eps(mesh);
  for (std::size_t i = 0; i < segs.size(); ++i)
    for (std::size_t j = i + 1; j < segs.size(); ++j) {
      const Seg &s = segs[i], &t = segs[j];
      if (!((s.lo.array() <= t.hi.array() + eps).all() && (t.lo.array() <= s.hi.array() + eps).all())) continue;
      const P2 a = project(mesh.points[s.a], k), b = project(mesh.points[s.b], k);
      const P2 c = project(mesh.points[t.a], k), d = project(mesh.points[t.b], k);
      if ((s.a == t.a && s.b == t.b) || (s.a == t.b && s.b == t.a)) return name + " uses an edge twice";
      if (s.a == t.a || s.a == t.b || s.b == t.a || s.b == t.b) {
        // sharing a vertex (consecutive edges, or a pinch): they may meet only there
        const P2& s_other = (s.a == t.a || s.a == t.b) ? b : a;
        const P2& t_other = (t.a == s.a || t.a == s.b) ? d : c;
        if ((orient(a, b, t_other) == 0 && between(a, b, t_other)) || (orient(c, d, s_other) == 0 && between(c, d, s_other)))
          return name + " folds back on itself";
        continue;
      }
      if (segments_meet(a, b, c, d)) return name + " has crossing or touching edges";
    }
  return "";
}

std::string check_facet_pair(const ExactPolyMesh& mesh, int ia, int ib) {
  const QFacet& A = mesh.facets[ia];
  const QFacet& B = mesh.facets[ib];
  const QVec na = to_qvec(A.normal), nb = to_qvec(B.normal);
  const std::string names = "facets " + std::to_string(ia) + " and " + std::to_string(ib);
  std::vector<int> va, vb;
  for (const auto& l : A.loops) va.insert(va.end(), l.begin(), l.end());
  for (const auto& l : B.loops) vb.insert(vb.end(), l.begin(), l.end());
  std::sort(va.begin(), va.end());
  std::sort(vb.begin(), vb.end());
  std::vector<int> shared;
  std::set_intersection(va.begin(), va.end(), vb.begin(), vb.end(), std::back_inserter(shared));
  auto is_shared_vertex = [&](const QVec& x) {
    for (int v : shared)
      if (mesh.points[v] == x) return true;
    return false;
  };
  const QVec d = cross(na, nb);
  if (is_zero(d)) {
    // parallel planes
    if (dot(na, mesh.points[vb[0]]) != A.offset) return "";
    // same plane: only shared vertices may touch
    const int k = drop_axis(A);
    auto check_side = [&](const QFacet& X, const QFacet& Y) -> bool {
      for (const auto& loop : X.loops)
        for (std::size_t i = 0; i < loop.size(); ++i) {
          const int a = loop[i], b = loop[(i + 1) % loop.size()];
          if (!std::binary_search(shared.begin(), shared.end(), a) &&
              locate_in_loops(mesh, Y.loops, k, mesh.points[a]) != Where::Outside)
            return false;
          const QVec mid = Q(1, 2) * (mesh.points[a] + mesh.points[b]);
          if (locate_in_loops(mesh, Y.loops, k, mid) != Where::Outside) return false;
          for (const auto& yl : Y.loops)
            for (std::size_t j = 0; j < yl.size(); ++j) {
              const int c = yl[j], e = yl[(j + 1) % yl.size()];
              if (c == a || c == b || e == a || e == b) continue;
              if (segments_meet(project(mesh.points[a], k), project(mesh.points[b], k), project(mesh.points[c], k),
                                project(mesh.points[e], k)))
                return false;
            }
        }
      return true;
    };
    if (!check_side(A, B) || !check_side(B, A)) return names + " overlap on a common plane";
    return "";
  }
  // Breakpoints of both boundaries on the line L = plane A ^ plane B.
  std::vector<std::pair<Q, QVec>> pts;
  auto collect = [&](const QFacet& X, const QVec& n_other, const Q& c_other) {
    for (const auto& loop : X.loops)
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const QVec& u = mesh.points[loop[i]];
        const QVec& v = mesh.points[loop[(i + 1) % loop.size()]];
        const Q su = dot(n_other, u) - c_other, sv = dot(n_other, v) - c_other;
        if (CGAL::is_zero(su)) pts.emplace_back(dot(d, u), u);
        if (CGAL::sign(su) * CGAL::sign(sv) < 0) {
          const QVec x = u + (su / (su - sv)) * (v - u);
          pts.emplace_back(dot(d, x), x);
        }
      }
  };
  collect(A, nb, B.offset);
  const std::size_t num_from_a = pts.size();
  if (num_from_a == 0) return "";
  collect(B, na, A.offset);
  if (pts.size() == num_from_a) return "";
  std::sort(pts.begin(), pts.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  pts.erase(std::unique(pts.begin(), pts.end(), [](const auto& x, const auto& y) { return x.first == y.first; }),
            pts.end());
  // edges of A whose opposite is in B
  auto on_shared_edge = [&](const QVec& x) {
    const int k = drop_axis(A);
    const P2 q = project(x, k);
    for (const auto& loop : A.loops)
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const int a = loop[i], b = loop[(i + 1) % loop.size()];
        if (!std::binary_search(shared.begin(), shared.end(), a) || !std::binary_search(shared.begin(), shared.end(), b))
          continue;
        bool in_b = false;
        for (const auto& bl : B.loops)
          for (std::size_t j = 0; j < bl.size(); ++j)
            if (bl[j] == b && bl[(j + 1) % bl.size()] == a) in_b = true;
        if (!in_b) continue;
        const P2 pa = project(mesh.points[a], k), pb = project(mesh.points[b], k);
        if (orient(pa, pb, q) == 0 && between(pa, pb, q)) return true;
      }
    return false;
  };
  auto test = [&](const QVec& x) -> bool {
    const Where wa = locate_in_facet(mesh, A, x);
    if (wa == Where::Outside) return true;
    const Where wb = locate_in_facet(mesh, B, x);
    if (wb == Where::Outside) return true;
    if (is_shared_vertex(x)) return true;
    if (wa == Where::Boundary && wb == Where::Boundary && on_shared_edge(x)) return true;
    return false;
  };
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!test(pts[i].second)) return names + " intersect";
    if (i + 1 < pts.size() && !test(Q(1, 2) * (pts[i].second + pts[i + 1].second))) return names + " intersect";
  }
  return "";
}

std::string check_no_intersections(const ExactPolyMesh& mesh, const std::vector<int>& facets) {
  std::vector<Box> boxes(mesh.facets.size());
  for (std::size_t f = 0; f < mesh.facets.size(); ++f)
    if (mesh.facets[f].alive) boxes[f] = facet_box(mesh, mesh.facets[f]);
  const double eps = box_eps(mesh);
  std::vector<char> in_list(mesh.facets.size(), 0);
  for (int f : facets) in_list[f] = 1;
  for (int f : facets) {
    if (!mesh.facets[f].alive) continue;
    for (std::size_t g = 0; g < mesh.facets.size(); ++g) {
      if (int(g) == f || !mesh.facets[g].alive) continue;
      if (in_list[g] && int(g) < f) continue;  // pair already checked
      if (!boxes[f].overlaps(boxes[g], eps)) continue;
      std::string r = check_facet_pair(mesh, f, static_cast<int>(g));
      if (!r.empty()) return r;
    }
  }
  return "";
}

}  // namespace subfab::unfold_detail
