// SPDX-License-Identifier: GPL-3.0-or-later
#include "unfold/exact_poly_mesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <unordered_map>

#include "subfab/core/error.h"
#include "subfab/unfold/lattice_directions.h"

namespace subfab::unfold_detail {

QVec operator+(const QVec& a, const QVec& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
QVec operator-(const QVec& a, const QVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
QVec operator*(const Q& s, const QVec& a) { return {s * a.x, s * a.y, s * a.z}; }
bool operator==(const QVec& a, const QVec& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
Q dot(const QVec& a, const QVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
QVec cross(const QVec& a, const QVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
QVec to_qvec(const std::array<int, 3>& v) { return {Q(v[0]), Q(v[1]), Q(v[2])}; }
bool is_zero(const QVec& a) { return CGAL::is_zero(a.x) && CGAL::is_zero(a.y) && CGAL::is_zero(a.z); }

namespace {

constexpr int kDenominator = 24;

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

int drop_axis(const QFacet& f) {
  for (int k = 0; k < 3; ++k)
    if (f.normal[k] != 0) return k;
  return 2;
}

struct P2 {
  Q u, v;
};

P2 project(const QVec& p, int k) { return {p[(k + 1) % 3], p[(k + 2) % 3]}; }

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

Vec3 to_model(const QVec& q, const LatticeFrame& frame) {
  const Vec3 v(CGAL::to_double(q.x), CGAL::to_double(q.y), CGAL::to_double(q.z));
  if (frame.step > 0) return frame.origin + frame.step * v;
  return v;
}

int add_point(ExactPolyMesh& mesh, const QVec& q) {
  mesh.points.push_back(q);
  mesh.approx.push_back(to_model(q, mesh.frame));
  return static_cast<int>(mesh.points.size()) - 1;
}

ExactPolyMesh to_exact(const PolyMesh& mesh, const LatticeFrame& frame) {
  ExactPolyMesh out;
  out.frame = frame;
  out.points.reserve(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& x = mesh.vertices[i];
    QVec q;
    if (frame.step > 0) {
      for (int k = 0; k < 3; ++k) {
        const double m = std::round((x[k] - frame.origin[k]) / frame.step * kDenominator);
        const double back = frame.origin[k] + frame.step * (m / kDenominator);
        if (!(std::abs(back - x[k]) <= 1e-6 * frame.step))
          throw InvalidArgumentError("vertex " + std::to_string(i) +
                                     " is not on the lattice of the polygonal mesh (grid step " +
                                     std::to_string(frame.step) + ")");
        q[k] = Q(m) / Q(kDenominator);
      }
    } else {
      q = {Q(x[0]), Q(x[1]), Q(x[2])};
    }
    out.points.push_back(q);
    out.approx.push_back(x);
  }
  const auto& dirs = lattice_directions();
  for (std::size_t f = 0; f < mesh.facets.size(); ++f) {
    const Facet& in = mesh.facets[f];
    if (in.loops.empty() || in.loops[0].size() < 3)
      throw InvalidArgumentError("facet " + std::to_string(f) + " has no outer loop");
    QFacet qf;
    qf.loops = in.loops;
    int normal = in.normal;
    if (normal < 0) {
      Vec3 nsum = Vec3::Zero();
      const auto& loop = in.loops[0];
      for (std::size_t i = 0; i < loop.size(); ++i)
        nsum += mesh.vertices[loop[i]].cross(mesh.vertices[loop[(i + 1) % loop.size()]]);
      const auto idx = lattice_direction_index(nsum, 1e-6);
      if (!idx)
        throw InvalidArgumentError("facet " + std::to_string(f) +
                                   " has a normal that is not one of the 26 lattice directions");
      normal = *idx;
    }
    if (normal >= 26) throw InvalidArgumentError("facet " + std::to_string(f) + ": normal index out of range");
    qf.normal_index = normal;
    qf.normal = dirs[normal];
    const QVec n = to_qvec(qf.normal);
    qf.offset = dot(n, out.points[in.loops[0][0]]);
    for (const auto& loop : in.loops)
      for (int v : loop) {
        if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertices.size())
          throw InvalidArgumentError("facet " + std::to_string(f) + " refers to a missing vertex");
        if (dot(n, out.points[v]) != qf.offset)
          throw InvalidArgumentError("facet " + std::to_string(f) + " is not planar (vertex " +
                                     std::to_string(v) + " is off its plane)");
      }
    out.facets.push_back(std::move(qf));
  }
  return out;
}

PolyMesh to_poly_mesh(const ExactPolyMesh& mesh) {
  PolyMesh out;
  std::vector<int> remap(mesh.points.size(), -1);
  for (const auto& f : mesh.facets) {
    if (!f.alive) continue;
    Facet g;
    g.normal = f.normal_index;
    for (const auto& loop : f.loops) {
      std::vector<int> l;
      for (int v : loop) {
        if (remap[v] < 0) {
          remap[v] = static_cast<int>(out.vertices.size());
          out.vertices.push_back(to_model(mesh.points[v], mesh.frame));
        }
        l.push_back(remap[v]);
      }
      g.loops.push_back(std::move(l));
    }
    out.facets.push_back(std::move(g));
  }
  return out;
}

Q loop_area2(const ExactPolyMesh& mesh, const QFacet& facet, const std::vector<int>& loop) {
  const int k = drop_axis(facet);
  Q sum(0);
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const P2 a = project(mesh.points[loop[i]], k);
    const P2 b = project(mesh.points[loop[(i + 1) % n]], k);
    sum += a.u * b.v - a.v * b.u;
  }
  return facet.normal[k] > 0 ? sum : -sum;
}

Where locate_in_facet(const ExactPolyMesh& mesh, const QFacet& facet, const QVec& p) {
  return locate_in_loops(mesh, facet.loops, drop_axis(facet), p);
}

std::string check_closed_manifold(const ExactPolyMesh& mesh) {
  // directed edge -> (facet, loop, index of its start corner)
  struct Corner {
    int facet, loop, index;
  };
  std::unordered_map<std::uint64_t, Corner> edges;
  std::unordered_map<int, int> num_corners;
  for (std::size_t f = 0; f < mesh.facets.size(); ++f) {
    const auto& facet = mesh.facets[f];
    if (!facet.alive) continue;
    for (std::size_t l = 0; l < facet.loops.size(); ++l) {
      const auto& loop = facet.loops[l];
      if (loop.size() < 3) return "facet " + std::to_string(f) + " has a loop with fewer than 3 corners";
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const int a = loop[i], b = loop[(i + 1) % loop.size()];
        if (a == b) return "facet " + std::to_string(f) + " has a zero-length edge";
        if (!edges.emplace(edge_key(a, b), Corner{int(f), int(l), int(i)}).second)
          return "edge " + std::to_string(a) + "-" + std::to_string(b) + " is used twice in one direction";
        ++num_corners[a];
      }
    }
  }
  for (const auto& [key, c] : edges) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    if (!edges.count(edge_key(b, a)))
      return "edge " + std::to_string(a) + "-" + std::to_string(b) + " has no opposite (surface not closed)";
  }
  // Each vertex: corners must form one fan cycle. From the corner starting
  // edge (v, w), the next corner around v starts edge (v, u) where (w, v)
  // ... precisely: corner c at v has incoming (p, v) and outgoing (v, n);
  // the opposite of (v, n) is (n, v), whose loop continues with (v, x):
  // that is the next corner around v.
  std::unordered_map<int, int> visited_fan;
  std::unordered_map<std::uint64_t, bool> seen;
  for (const auto& [key, c0] : edges) {
    const int v = static_cast<int>(key >> 32);
    if (visited_fan.count(v)) continue;
    int count = 0;
    std::uint64_t cur = key;
    do {
      ++count;
      const int n = static_cast<int>(cur & 0xffffffffu);
      const Corner& opp = edges.at(edge_key(n, v));
      const auto& loop = mesh.facets[opp.facet].loops[opp.loop];
      const int x = loop[(opp.index + 2) % loop.size()];
      cur = edge_key(v, x);
      if (count > num_corners[v] + 1) break;
    } while (cur != key);
    if (count != num_corners[v])
      return "vertex " + std::to_string(v) + " is non-manifold (" + std::to_string(num_corners[v]) +
             " corners, fan of " + std::to_string(count) + ")";
    visited_fan[v] = 1;
  }
  return "";
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

namespace {
int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}
}  // namespace

std::optional<std::vector<int>> merge_coplanar_neighbours(ExactPolyMesh& mesh, const std::vector<int>& only) {
  std::vector<char> selected(mesh.facets.size(), only.empty() ? 1 : 0);
  for (int f : only) selected[f] = 1;
  std::unordered_map<std::uint64_t, int> owner;
  for (std::size_t f = 0; f < mesh.facets.size(); ++f) {
    if (!mesh.facets[f].alive) continue;
    for (const auto& loop : mesh.facets[f].loops)
      for (std::size_t i = 0; i < loop.size(); ++i) owner[edge_key(loop[i], loop[(i + 1) % loop.size()])] = int(f);
  }
  std::vector<int> parent(mesh.facets.size());
  std::iota(parent.begin(), parent.end(), 0);
  bool any = false;
  for (std::size_t f = 0; f < mesh.facets.size(); ++f) {
    const auto& F = mesh.facets[f];
    if (!F.alive) continue;
    for (const auto& loop : F.loops)
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const auto it = owner.find(edge_key(loop[(i + 1) % loop.size()], loop[i]));
        if (it == owner.end() || it->second == int(f)) continue;
        if (!selected[f] && !selected[it->second]) continue;
        const auto& G = mesh.facets[it->second];
        if (G.normal_index == F.normal_index && G.offset == F.offset) {
          const int ra = find_root(parent, int(f)), rb = find_root(parent, it->second);
          if (ra != rb) {
            parent[std::max(ra, rb)] = std::min(ra, rb);
            any = true;
          }
        }
      }
  }
  std::vector<int> changed;
  if (!any) return changed;
  std::map<int, std::vector<int>> groups;
  for (std::size_t f = 0; f < mesh.facets.size(); ++f)
    if (mesh.facets[f].alive) groups[find_root(parent, int(f))].push_back(int(f));
  for (auto& [root, members] : groups) {
    if (members.size() < 2) continue;
    std::unordered_map<std::uint64_t, int> dir;
    std::vector<std::pair<int, int>> list;
    for (int f : members)
      for (const auto& loop : mesh.facets[f].loops)
        for (std::size_t i = 0; i < loop.size(); ++i) list.emplace_back(loop[i], loop[(i + 1) % loop.size()]);
    for (auto& e : list) dir[edge_key(e.first, e.second)] = 1;
    std::map<int, int> next;  // start -> end (ordered: deterministic)
    for (auto& e : list) {
      if (dir.count(edge_key(e.second, e.first))) continue;
      if (next.count(e.first)) return std::nullopt;  // pinched region
      next[e.first] = e.second;
    }
    std::vector<std::vector<int>> loops;
    while (!next.empty()) {
      std::vector<int> loop;
      int start = next.begin()->first, v = start;
      do {
        loop.push_back(v);
        auto it = next.find(v);
        if (it == next.end()) return std::nullopt;
        const int w = it->second;
        next.erase(it);
        v = w;
      } while (v != start);
      loops.push_back(std::move(loop));
    }
    QFacet merged = mesh.facets[root];
    merged.loops.clear();
    int num_outer = 0;
    std::vector<std::vector<int>> holes;
    for (auto& l : loops) {
      if (loop_area2(mesh, merged, l) > 0) {
        ++num_outer;
        merged.loops.insert(merged.loops.begin(), l);
      } else {
        holes.push_back(l);
      }
    }
    if (num_outer != 1) return std::nullopt;
    merged.loops.insert(merged.loops.end(), holes.begin(), holes.end());
    mesh.facets[root] = std::move(merged);
    for (int f : members)
      if (f != root) mesh.facets[f].alive = false;
    changed.push_back(root);
  }
  return changed;
}

std::vector<int> remove_two_facet_vertices(ExactPolyMesh& mesh) {
  std::vector<int> changed;
  bool again = true;
  while (again) {
    again = false;
    std::unordered_map<int, std::vector<std::pair<int, int>>> corners;  // v -> (facet, loop)
    for (std::size_t f = 0; f < mesh.facets.size(); ++f) {
      if (!mesh.facets[f].alive) continue;
      for (std::size_t l = 0; l < mesh.facets[f].loops.size(); ++l)
        for (int v : mesh.facets[f].loops[l]) corners[v].emplace_back(int(f), int(l));
    }
    std::vector<int> candidates;
    for (const auto& [v, cs] : corners)
      if (cs.size() == 2 && cs[0].first != cs[1].first) candidates.push_back(v);
    std::sort(candidates.begin(), candidates.end());
    std::vector<char> touched(mesh.facets.size(), 0);
    for (int v : candidates) {
      const auto& cs = corners[v];
      if (touched[cs[0].first] || touched[cs[1].first]) continue;  // re-scan next round
      auto& l0 = mesh.facets[cs[0].first].loops[cs[0].second];
      auto& l1 = mesh.facets[cs[1].first].loops[cs[1].second];
      if (l0.size() <= 3 || l1.size() <= 3) continue;
      const auto i0 = std::find(l0.begin(), l0.end(), v) - l0.begin();
      const QVec& p = mesh.points[l0[(i0 + l0.size() - 1) % l0.size()]];
      const QVec& q = mesh.points[l0[(i0 + 1) % l0.size()]];
      const QVec& x = mesh.points[v];
      if (!is_zero(cross(x - p, q - x)) || !(dot(x - p, q - x) > 0)) continue;
      l0.erase(l0.begin() + i0);
      l1.erase(std::find(l1.begin(), l1.end(), v));
      touched[cs[0].first] = touched[cs[1].first] = 1;
      changed.push_back(cs[0].first);
      changed.push_back(cs[1].first);
      again = true;
    }
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  return changed;
}

bool has_coplanar_neighbours(const ExactPolyMesh& mesh) {
  std::unordered_map<std::uint64_t, int> owner;
  for (std::size_t f = 0; f < mesh.facets.size(); ++f) {
    if (!mesh.facets[f].alive) continue;
    for (const auto& loop : mesh.facets[f].loops)
      for (std::size_t i = 0; i < loop.size(); ++i) owner[edge_key(loop[i], loop[(i + 1) % loop.size()])] = int(f);
  }
  for (const auto& [key, f] : owner) {
    const auto it = owner.find(edge_key(int(key & 0xffffffffu), int(key >> 32)));
    if (it == owner.end() || it->second == f) continue;
    const auto &F = mesh.facets[f], &G = mesh.facets[it->second];
    if (F.normal_index == G.normal_index && F.offset == G.offset) return true;
  }
  return false;
}

double facet_area(const ExactPolyMesh& mesh, int f) {
  const QFacet& facet = mesh.facets[f];
  Q sum(0);
  for (const auto& loop : facet.loops) sum += loop_area2(mesh, facet, loop);
  // projected area * |n| / |n[k]| = true area (|n[k]| = 1); in lattice units
  const double n_len = std::sqrt(double(facet.normal[0] * facet.normal[0] + facet.normal[1] * facet.normal[1] +
                                        facet.normal[2] * facet.normal[2]));
  const double s = mesh.frame.step > 0 ? mesh.frame.step : 1.0;
  return 0.5 * CGAL::to_double(sum) * n_len * s * s;
}

}  // namespace subfab::unfold_detail
