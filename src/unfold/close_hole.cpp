// SPDX-License-Identifier: GPL-3.0-or-later
//! \file close_hole.cpp
//! Closing the hole left by deleted facets (thesis Section 3.3.2, Figure
//! 3.11): a circular buffer of the neighbour facets around the hole, a
//! half-line between each adjacent pair along the line where their planes
//! meet, and repeated closing of the entry whose two half-lines meet
//! closest, until two or three entries are left.
#include "unfold/close_hole.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "unfold/edge_key.h"

namespace subfab::unfold_detail {

namespace {

// One entry of the circular buffer: a neighbour facet whose boundary along
// the hole runs from e (where it leaves the hole boundary, in its own loop
// order) back to s. Its closing chain will be e, head..., tail..., s.
struct Entry {
  int facet;
  int s, e;
  std::vector<int> head;  // new vertices after e (last = meeting vertex with the next entry)
  std::vector<int> tail;  // new vertices before s (first = meeting vertex with the previous entry)
};

// Half-line between entry i and entry i+1.
struct HalfLine {
  int origin;
  QVec dir;
};

class HoleCloser {
 public:
  HoleCloser(ExactPolyMesh& mesh, const std::unordered_map<std::uint64_t, int>& owner,
             const std::vector<int>& region, double max_extension, const detail::SurfaceDistance* reference,
             double max_distance)
      : mesh_(mesh),
        owner_(owner),
        region_(region),
        max_extension_(max_extension),
        reference_(reference),
        max_distance_(max_distance) {}

  // Returns "" on success (mesh modified, region facets dead), else the reason
  // (mesh possibly half-modified: the caller restores it).
  std::string run() {
    std::set<int> in_region(region_.begin(), region_.end());
    for (int f : region_) {
      if (!mesh_.facets[f].alive) return "facet " + std::to_string(f) + " no longer exists";
      if (mesh_.facets[f].loops.size() > 1) return "facet " + std::to_string(f) + " has holes";
    }
    const auto& owner = owner_;
    // Boundary of the region (region loops are CCW from outside).
    std::map<int, int> next;
    for (int f : region_)
      for (const auto& loop : mesh_.facets[f].loops)
        for (std::size_t i = 0; i < loop.size(); ++i) {
          const int a = loop[i], b = loop[(i + 1) % loop.size()];
          const auto it = owner.find(edge_key(b, a));
          if (it == owner.end()) return "mesh is not closed around the facet";
          if (in_region.count(it->second)) continue;
          if (next.count(a)) return "the facets to delete touch themselves at vertex " + std::to_string(a);
          next[a] = b;
        }
    if (next.empty()) return "the facets to delete have no boundary";
    std::vector<int> cycle;
    {
      int v = next.begin()->first;
      do {
        cycle.push_back(v);
        const auto it = next.find(v);
        if (it == next.end()) return "the boundary of the facets to delete is not a single loop";
        v = it->second;
      } while (v != cycle.front() && cycle.size() <= next.size());
      if (cycle.size() != next.size()) return "the facets to delete do not form a disk (several boundary loops)";
    }
    {
      std::set<int> verts;
      for (int f : region_)
        for (int v : mesh_.facets[f].loops[0]) verts.insert(v);
      for (int v : verts) region_points_.push_back(mesh_.approx[v]);
    }
    const std::size_t m = cycle.size();
    std::vector<int> nb(m);
    for (std::size_t j = 0; j < m; ++j) nb[j] = owner.at(edge_key(cycle[(j + 1) % m], cycle[j]));
    std::size_t start = m;
    for (std::size_t j = 0; j < m; ++j)
      if (nb[j] != nb[(j + m - 1) % m]) {
        start = j;
        break;
      }
    if (start == m) return "the hole is surrounded by a single facet";
    std::set<int> seen;
    for (std::size_t r = 0; r < m;) {
      const std::size_t j = (start + r) % m;
      Entry entry{nb[j], cycle[j], -1, {}, {}};
      std::size_t len = 0;
      while (r + len < m && nb[(start + r + len) % m] == entry.facet) ++len;
      entry.e = cycle[(start + r + len) % m];
      if (!seen.insert(entry.facet).second)
        return "facet " + std::to_string(entry.facet) + " borders the hole twice";
      buffer_.push_back(std::move(entry));
      r += len;
    }
    cycle_ = cycle;
    region_normal_ = Vec3::Zero();
    for (int f : region_) {
      const auto& l = mesh_.facets[f].loops[0];
      for (std::size_t i = 0; i < l.size(); ++i) region_normal_ += mesh_.approx[l[i]].cross(mesh_.approx[l[(i + 1) % l.size()]]);
    }
    const std::size_t k = buffer_.size();
    for (std::size_t i = 0; i < k; ++i) {
      auto line = initial_half_line(buffer_[i], buffer_[(i + 1) % k], owner);
      if (!line) return reason_;
      lines_.push_back(*line);
    }
    while (buffer_.size() > 3) {
      if (std::string r = step(); !r.empty()) return r;
    }
    if (buffer_.size() == 3) {
      if (std::string r = finish_three(); !r.empty()) return r;
    } else if (buffer_.size() == 2) {
      if (std::string r = finish_two(); !r.empty()) return r;
    } else {
      return "the hole is surrounded by a single facet";
    }
    return apply();
  }

 private:
  const QVec normal(int f) const { return to_qvec(mesh_.facets[f].normal); }

  std::optional<HalfLine> initial_half_line(const Entry& a, const Entry& b,
                                            const std::unordered_map<std::uint64_t, int>& owner) {
    const int o = a.e;
    QVec d = cross(normal(a.facet), normal(b.facet));
    if (is_zero(d)) {
      reason_ = "neighbours " + std::to_string(a.facet) + " and " + std::to_string(b.facet) + " are parallel";
      return std::nullopt;
    }
    // Shared edge X -> o in a (and o -> X in b): continue it.
    const auto& loops = mesh_.facets[a.facet].loops;
    for (const auto& loop : loops) {
      const auto it = std::find(loop.begin(), loop.end(), o);
      if (it == loop.end()) continue;
      const int x = loop[(it - loop.begin() + loop.size() - 1) % loop.size()];
      const auto ob = owner.find(edge_key(o, x));
      if (ob != owner.end() && ob->second == b.facet) {
        const Q s = dot(d, mesh_.points[o] - mesh_.points[x]);
        if (s < 0) d = Q(-1) * d;
        return HalfLine{o, d};
      }
    }
    // No shared edge: the new edge must run into the corner of the deleted
    // region at o. Seen along the region's normal, that corner spans from
    // the outgoing boundary edge counter-clockwise to the incoming one.
    const std::size_t j = static_cast<std::size_t>(std::find(cycle_.begin(), cycle_.end(), o) - cycle_.begin());
    const std::size_t m = cycle_.size();
    const Vec3 x = mesh_.approx[o];
    const Vec3 nr = region_normal_.normalized();
    auto flat = [&](const Vec3& v) { return Vec3(v - v.dot(nr) * nr); };
    const Vec3 u1 = flat(mesh_.approx[cycle_[(j + 1) % m]] - x).normalized();
    const Vec3 u2 = flat(mesh_.approx[cycle_[(j + m - 1) % m]] - x).normalized();
    auto ccw_angle = [&](const Vec3& from, const Vec3& to) {
      const double angle = std::atan2(nr.dot(from.cross(to)), from.dot(to));
      return angle < 0 ? angle + 2 * 3.14159265358979323846 : angle;
    };
    const double sector = ccw_angle(u1, u2);
    const Vec3 dv = flat(Vec3(CGAL::to_double(d.x), CGAL::to_double(d.y), CGAL::to_double(d.z))).normalized();
    const double half = 0.5 * sector;
    // angular distance of +d and -d from the sector's bisector
    auto off_bisector = [&](const Vec3& v) { return std::abs(ccw_angle(u1, v) - half); };
    const double plus = off_bisector(dv), minus = off_bisector(-dv);
    if (!(dv.norm() > 0.5) || std::abs(plus - minus) < 1e-9) {
      reason_ = "cannot tell which way the edge between facets " + std::to_string(a.facet) + " and " +
                std::to_string(b.facet) + " extends";
      return std::nullopt;
    }
    if (minus < plus) d = Q(-1) * d;
    return HalfLine{o, d};
  }

  // Intersection of the half-lines on both sides of entry i (lines_[i-1]
  // and lines_[i]); returns the parameters' point and a distance key.
  struct Closure {
    QVec p;
    Q key;
  };
  std::optional<Closure> intersect(const HalfLine& r1, const HalfLine& r2, bool full_lines = false) const {
    const QVec& o1 = mesh_.points[r1.origin];
    const QVec& o2 = mesh_.points[r2.origin];
    if (r1.origin == r2.origin) return Closure{o1, Q(0)};
    const QVec c = cross(r1.dir, r2.dir);
    if (is_zero(c)) return std::nullopt;
    const QVec w = o2 - o1;
    const Q cc = dot(c, c);
    const Q t = dot(cross(w, r2.dir), c) / cc;
    const Q s = dot(cross(w, r1.dir), c) / cc;
    if (!full_lines && (t < 0 || s < 0)) return std::nullopt;
    const QVec p = o1 + t * r1.dir;
    if (!(p == o2 + s * r2.dir)) return std::nullopt;  // skew lines (not coplanar)
    const QVec a = p - o1, b = p - o2;
    const Q la = dot(a, a), lb = dot(b, b);
    return Closure{p, la > lb ? la : lb};
  }

  bool within_extension(const QVec& p) const {
    const Vec3 x = to_model(p, mesh_.frame);
    if (reference_ && (*reference_)(x) > max_distance_) return false;
    if (max_extension_ <= 0) return true;
    for (const Vec3& v : region_points_)
      if ((x - v).norm() <= max_extension_) return true;
    return false;
  }

  int point_id(const QVec& p, std::initializer_list<int> candidates) {
    for (int c : candidates)
      if (mesh_.points[c] == p) return c;
    for (int c : created_)
      if (mesh_.points[c] == p) return c;
    const int id = add_point(mesh_, p);
    created_.push_back(id);
    return id;
  }

  void close_entry(const Entry& entry, int p) {
    std::vector<int> chain{entry.e};
    auto push = [&](int v) {
      if (chain.back() != v) chain.push_back(v);
    };
    for (int v : entry.head) push(v);
    if (p >= 0) push(p);
    for (int v : entry.tail) push(v);
    push(entry.s);
    chains_[entry.facet] = std::move(chain);
  }

  std::string step() {
    const std::size_t k = buffer_.size();
    std::optional<std::size_t> best;
    std::optional<Closure> best_closure;
    // Half-lines first; when no two meet, whole lines (the exact validation
    // afterwards rejects a closure that folds the surface over).
    for (int pass = 0; pass < 2 && !best; ++pass)
      for (std::size_t i = 0; i < k; ++i) {
        const auto c = intersect(lines_[(i + k - 1) % k], lines_[i], pass == 1);
        if (!c || !within_extension(c->p)) continue;
        if (!best_closure || c->key < best_closure->key) {
          best = i;
          best_closure = c;
        }
      }
    if (!best) return "no two adjacent half-lines meet: the neighbourhood cannot be closed by extending its facets";
    const std::size_t i = *best;
    const std::size_t ip = (i + k - 1) % k, in = (i + 1) % k;
    const int o1 = lines_[ip].origin, o2 = lines_[i].origin;
    const int p = point_id(best_closure->p, {o1, o2});
    close_entry(buffer_[i], p);
    if (buffer_[ip].head.empty() ? buffer_[ip].e != p : buffer_[ip].head.back() != p) buffer_[ip].head.push_back(p);
    if (buffer_[in].tail.empty() ? buffer_[in].s != p : buffer_[in].tail.front() != p)
      buffer_[in].tail.insert(buffer_[in].tail.begin(), p);
    // New half-line between ip and in, away from where the two old ones came from.
    QVec d = cross(normal(buffer_[ip].facet), normal(buffer_[in].facet));
    if (is_zero(d))
      return "facets " + std::to_string(buffer_[ip].facet) + " and " + std::to_string(buffer_[in].facet) +
             " would meet but are parallel";
    // Toward the rest of the hole (the origins of the other half-lines);
    // failing that, away from where the two closed half-lines came from.
    const QVec& pp = mesh_.points[p];
    QVec toward{Q(0), Q(0), Q(0)};
    for (std::size_t j = 0; j < k; ++j)
      if (j != ip && j != i) toward = toward + (mesh_.points[lines_[j].origin] - pp);
    Q s = dot(d, toward);
    if (CGAL::is_zero(s)) s = -dot(d, (mesh_.points[o1] - pp) + (mesh_.points[o2] - pp));
    if (CGAL::is_zero(s)) return "ambiguous continuation at a new vertex";
    if (s < 0) d = Q(-1) * d;
    HalfLine line{p, d};
    // Remove entry i; line ip becomes the new line.
    buffer_.erase(buffer_.begin() + static_cast<std::ptrdiff_t>(i));
    lines_[ip] = line;
    lines_.erase(lines_.begin() + static_cast<std::ptrdiff_t>(i));
    return "";
  }

  std::string finish_three() {
    // The three planes meet in one point (or the hole cannot be closed).
    const QVec n0 = normal(buffer_[0].facet), n1 = normal(buffer_[1].facet), n2 = normal(buffer_[2].facet);
    const QVec c12 = cross(n1, n2), c20 = cross(n2, n0), c01 = cross(n0, n1);
    const Q det = dot(n0, c12);
    if (CGAL::is_zero(det)) return "the last three facets around the hole do not meet in a point";
    const QVec x = (Q(1) / det) * (mesh_.facets[buffer_[0].facet].offset * c12 +
                                   mesh_.facets[buffer_[1].facet].offset * c20 +
                                   mesh_.facets[buffer_[2].facet].offset * c01);
    if (!within_extension(x)) return "closing the hole would move the surface too far";
    const int p = point_id(x, {lines_[0].origin, lines_[1].origin, lines_[2].origin});
    for (const Entry& e : buffer_) close_entry(e, p);
    return "";
  }

  std::string finish_two() {
    const HalfLine &r1 = lines_[0], &r2 = lines_[1];
    const QVec w = mesh_.points[r2.origin] - mesh_.points[r1.origin];
    if (!is_zero(cross(w, r1.dir)) || dot(w, r1.dir) < 0 || !is_zero(cross(r1.dir, r2.dir)) ||
        dot(r1.dir, r2.dir) > 0)
      return "the last two facets around the hole do not meet along one edge";
    for (const Entry& e : buffer_) close_entry(e, -1);
    return "";
  }

  std::string apply() {
    for (const auto& [f, chain] : chains_) {
      auto& loops = mesh_.facets[f].loops;
      bool done = false;
      for (auto& loop : loops) {
        const auto it = std::find(loop.begin(), loop.end(), chain.front());
        if (it == loop.end()) continue;
        const std::size_t n = loop.size();
        const std::size_t ie = static_cast<std::size_t>(it - loop.begin());
        std::size_t len = 0;  // number of vertices strictly between e and s
        while (len < n && loop[(ie + 1 + len) % n] != chain.back()) ++len;
        if (len >= n) return "internal: hole chain of facet " + std::to_string(f) + " not found";
        std::vector<int> fresh;
        fresh.reserve(n - len + chain.size());
        // loop from s around to e, then the chain interior
        for (std::size_t r = 0; r + len + 1 < n + 1; ++r) {
          const std::size_t idx = (ie + 1 + len + r) % n;
          fresh.push_back(loop[idx]);
          if (idx == ie) break;
        }
        for (std::size_t c = 1; c + 1 < chain.size(); ++c) fresh.push_back(chain[c]);
        loop = std::move(fresh);
        done = true;
        break;
      }
      if (!done) return "internal: facet " + std::to_string(f) + " lost its hole boundary";
    }
    for (int f : region_) mesh_.facets[f].alive = false;
    return "";
  }

  ExactPolyMesh& mesh_;
  const std::unordered_map<std::uint64_t, int>& owner_;
  std::vector<int> region_;
  double max_extension_;
  const detail::SurfaceDistance* reference_;
  double max_distance_;
  std::vector<Vec3> region_points_;
  std::vector<int> cycle_;
  Vec3 region_normal_ = Vec3::Zero();
  std::vector<Entry> buffer_;
  std::vector<HalfLine> lines_;  // lines_[i]: between buffer_[i] and buffer_[i+1]
  std::map<int, std::vector<int>> chains_;
  std::vector<int> created_;
  std::string reason_;
};

}  // namespace

std::string close_hole(ExactPolyMesh& mesh, const std::unordered_map<std::uint64_t, int>& owner,
                       const std::vector<int>& region, const CloseHoleLimits& limits) {
  return HoleCloser(mesh, owner, region, limits.max_extension, limits.reference, limits.max_distance).run();
}

}  // namespace subfab::unfold_detail
