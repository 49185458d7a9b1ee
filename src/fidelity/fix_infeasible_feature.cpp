// SPDX-License-Identifier: GPL-3.0-or-later
//! \file fix_infeasible_feature.cpp
//! The local edits of stage A of repair_infeasible_features() (thesis
//! Section 4.3.5, local version): what they are and in which order they are
//! tried, see fix_infeasible_feature.h.
#include "fidelity/fix_infeasible_feature.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <utility>

namespace subfab::detail {
namespace {

//! Splits the edge (a, b) at `x` (reference point `xr`): each of its two faces
//! (u, v, o) becomes (u, m, o) (same id) and (m, v, o) (appended).
void split_edge(RepairWork& w, const std::vector<int>& star_a, int a, int b, const Vec3& x, const Vec3& xr) {
  const int m = static_cast<int>(w.mesh.vertices.size());
  w.mesh.vertices.push_back(x);
  w.reference.vertices.push_back(xr);
  for (int f : star_a) {
    Triangle& t = w.mesh.faces[static_cast<std::size_t>(f)];
    for (int c = 0; c < 3; ++c) {
      const int u = t[c], v = t[(c + 1) % 3], o = t[(c + 2) % 3];
      if (!((u == a && v == b) || (u == b && v == a))) continue;
      t = {u, m, o};
      w.mesh.faces.push_back({m, v, o});
      break;
    }
  }
  w.reference.faces = w.mesh.faces;
}

//! Splits the faces around p along the three coordinate planes through p
//! (each corner at p then lies in one closed orthant); the cut points get
//! the plane's coordinate exactly. Returns false when nothing was split.
bool split_along_planes(RepairWork& w, int p) {
  bool any = false;
  const Vec3 pp = w.mesh.vertices[static_cast<std::size_t>(p)];
  for (int k = 0; k < 3; ++k)
    for (bool again = true; again;) {
      again = false;
      const std::vector<std::vector<int>> star = vertex_stars(w.mesh);
      for (int f : star[static_cast<std::size_t>(p)]) {
        const Triangle t = w.mesh.faces[static_cast<std::size_t>(f)];
        const int c = t[0] == p ? 0 : (t[1] == p ? 1 : 2);
        const int q = t[(c + 1) % 3], r = t[(c + 2) % 3];
        const Vec3& qq = w.mesh.vertices[static_cast<std::size_t>(q)];
        const Vec3& rr = w.mesh.vertices[static_cast<std::size_t>(r)];
        if (!((qq[k] < pp[k] && rr[k] > pp[k]) || (qq[k] > pp[k] && rr[k] < pp[k]))) continue;
        const double s = (pp[k] - qq[k]) / (rr[k] - qq[k]);
        Vec3 x = qq + s * (rr - qq);
        x[k] = pp[k];
        const Vec3& qr = w.reference.vertices[static_cast<std::size_t>(q)];
        const Vec3& rr_ref = w.reference.vertices[static_cast<std::size_t>(r)];
        split_edge(w, star[static_cast<std::size_t>(q)], q, r, x, qr + s * (rr_ref - qr));
        any = again = true;
        break;
      }
    }
  return any;
}

//! Does a face normal turn from `before` to `after` by less than ~75 degrees
//! (cosine > 1/4; false when either is zero: a degenerate face)?
bool turns_less_than_75_degrees(const Vec3& before, const Vec3& after) {
  return after.dot(before) > 0.25 * after.norm() * before.norm();
}

//! Moves the vertices `ids` to `positions` (coordinates that change by at
//! most w.coordinate_noise kept as they are) unless a face around them would
//! flip or degenerate or a vertex would leave the deviation cap; returns
//! whether it moved them.
bool move_vertices(RepairWork& w, const std::vector<std::vector<int>>& star, const std::vector<int>& ids,
                   std::vector<Vec3> positions, double cap) {
  for (std::size_t i = 0; i < ids.size(); ++i)
    for (int k = 0; k < 3; ++k) {  // rounding noise: keep the coordinate (see RepairWork)
      const double now = w.mesh.vertices[static_cast<std::size_t>(ids[i])][k];
      if (std::abs(positions[i][k] - now) <= w.coordinate_noise) positions[i][k] = now;
    }
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (!((positions[i] - w.reference.vertices[static_cast<std::size_t>(ids[i])]).norm() <= cap)) return false;
  std::vector<int> faces;
  for (int v : ids) faces.insert(faces.end(), star[static_cast<std::size_t>(v)].begin(), star[static_cast<std::size_t>(v)].end());
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  std::vector<Vec3> before;
  for (int f : faces) before.push_back(face_normal_scaled(w.mesh, static_cast<std::size_t>(f)));
  std::vector<Vec3> old;
  for (int v : ids) old.push_back(w.mesh.vertices[static_cast<std::size_t>(v)]);
  for (std::size_t i = 0; i < ids.size(); ++i) w.mesh.vertices[static_cast<std::size_t>(ids[i])] = positions[i];
  bool ok = true;
  for (std::size_t i = 0; i < faces.size() && ok; ++i) {
    const Vec3 n = face_normal_scaled(w.mesh, static_cast<std::size_t>(faces[i]));
    ok = turns_less_than_75_degrees(before[i], n);
  }
  if (!ok)
    for (std::size_t i = 0; i < ids.size(); ++i) w.mesh.vertices[static_cast<std::size_t>(ids[i])] = old[i];
  return ok;
}

//! Nearest positions of v (one per milling axis, where one exists) at which
//! every face around v faces that axis with a margin: then v and the edges at
//! v are coverable (a common axis sees the whole star; see
//! find_infeasible_features.h). The normal of face (v, q, r) at position x is
//! q x r + x x (q - r), linear in x, so each face gives a half-space
//! g.x >= h; the nearest point of their intersection is the projection of v
//! onto the span of at most three active constraints (enumerated).
std::vector<Vec3> axis_candidates(const Mesh& mesh, const std::vector<std::vector<int>>& star, int v) {
  const Vec3 p = mesh.vertices[static_cast<std::size_t>(v)];
  std::vector<Vec3> out;
  for (int axis = 0; axis < 6; ++axis)
    for (double margin : {0.02, 0.1}) {
      Vec3 a = Vec3::Zero();
      a[axis / 2] = axis % 2 == 0 ? 1.0 : -1.0;
      std::vector<Vec3> g;
      std::vector<double> h;
      bool possible = true;
      for (int f : star[static_cast<std::size_t>(v)]) {
        const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
        const int c = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
        const Vec3& q = mesh.vertices[static_cast<std::size_t>(t[(c + 1) % 3])];
        const Vec3& r = mesh.vertices[static_cast<std::size_t>(t[(c + 2) % 3])];
        const Vec3 gi = (q - r).cross(a);
        const double hi = margin * (q - p).cross(r - p).norm() - a.dot(q.cross(r));
        if (gi.squaredNorm() == 0) {
          possible = possible && hi <= 0;
          continue;
        }
        g.push_back(gi);
        h.push_back(hi);
      }
      if (!possible) continue;
      const std::size_t m = g.size();
      const auto feasible = [&](const Vec3& x) {
        for (std::size_t i = 0; i < m; ++i)
          if (g[i].dot(x) < h[i] - 1e-12 * g[i].norm() * (x.norm() + 1)) return false;
        return true;
      };
      std::optional<Vec3> best;
      const auto consider = [&](const Vec3& x) {
        if (x.allFinite() && feasible(x) && (!best || (x - p).squaredNorm() < (*best - p).squaredNorm())) best = x;
      };
      consider(p);
      for (std::size_t i = 0; i < m; ++i) {
        consider(p + (h[i] - g[i].dot(p)) / g[i].squaredNorm() * g[i]);
        for (std::size_t j = i + 1; j < m; ++j) {
          Eigen::Matrix<double, 3, 2> G;
          G << g[i], g[j];
          const Eigen::Matrix2d A = G.transpose() * G;
          if (std::abs(A.determinant()) <= 1e-12 * A.norm() * A.norm()) continue;
          const Eigen::Vector2d rhs(h[i] - g[i].dot(p), h[j] - g[j].dot(p));
          consider(p + G * A.inverse() * rhs);
          for (std::size_t k = j + 1; k < m; ++k) {
            Eigen::Matrix3d M;
            M << g[i].transpose(), g[j].transpose(), g[k].transpose();
            if (std::abs(M.determinant()) <= 1e-12 * M.norm() * M.norm() * M.norm()) continue;
            consider(M.inverse() * Vec3(h[i], h[j], h[k]));
          }
        }
      }
      if (best && *best != p) out.push_back(*best);
    }
  return out;
}

//! Candidate positions for vertex v, nearest first: towards the centroid of
//! its neighbours, onto the line through two neighbours (a straightened
//! crease), onto the plane of a face across its link (a flattened corner).
std::vector<Vec3> move_candidates(const Mesh& mesh, const std::vector<std::vector<int>>& star, int v) {
  const Vec3 p = mesh.vertices[static_cast<std::size_t>(v)];
  std::vector<int> nb;
  std::vector<std::pair<int, int>> link;
  for (int f : star[static_cast<std::size_t>(v)]) {
    const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
    const int c = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
    nb.push_back(t[(c + 1) % 3]);
    link.emplace_back(t[(c + 1) % 3], t[(c + 2) % 3]);
  }
  std::sort(nb.begin(), nb.end());
  nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
  std::vector<Vec3> out;
  Vec3 centroid = Vec3::Zero();
  for (int u : nb) centroid += mesh.vertices[static_cast<std::size_t>(u)];
  centroid /= static_cast<double>(nb.size());
  for (double s : {0.0625, 0.125, 0.25, 0.5, 0.75, 1.0}) out.push_back(p + s * (centroid - p));
  for (std::size_t i = 0; i < nb.size(); ++i)
    for (std::size_t j = i + 1; j < nb.size(); ++j) {
      const Vec3& a = mesh.vertices[static_cast<std::size_t>(nb[i])];
      const Vec3 d = mesh.vertices[static_cast<std::size_t>(nb[j])] - a;
      const double s = (p - a).dot(d) / d.squaredNorm();
      if (s > 0 && s < 1) out.push_back(a + s * d);
    }
  for (const auto& [a, b] : link)
    for (int f : star[static_cast<std::size_t>(a)]) {  // the face across (a, b): b -> a, not at v
      const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
      if (std::find(t.begin(), t.end(), v) != t.end() || std::find(t.begin(), t.end(), b) == t.end()) continue;
      const Vec3 n = face_unit_normal(mesh, static_cast<std::size_t>(f));
      if (n.allFinite()) out.push_back(p - (p - mesh.vertices[static_cast<std::size_t>(a)]).dot(n) * n);
    }
  const std::vector<Vec3> axis = axis_candidates(mesh, star, v);
  out.insert(out.end(), axis.begin(), axis.end());
  std::stable_sort(out.begin(), out.end(),
                   [&](const Vec3& x, const Vec3& y) { return (x - p).squaredNorm() < (y - p).squaredNorm(); });
  return out;
}

//! Laplacian smoothing (Jacobi, factor 1/2) of the vertices within `rings`-1
//! rings of v, the ring `rings` fixed.
std::vector<Vec3> smoothed_ring(const Mesh& mesh, const std::vector<std::vector<int>>& star,
                                const std::vector<int>& movable, int steps) {
  std::vector<Vec3> pos;
  for (int u : movable) pos.push_back(mesh.vertices[static_cast<std::size_t>(u)]);
  Mesh m = mesh;  // positions being smoothed
  for (int step = 0; step < steps; ++step) {
    std::vector<Vec3> next = pos;
    for (std::size_t i = 0; i < movable.size(); ++i) {
      const int v = movable[i];
      Vec3 sum = Vec3::Zero();
      int n = 0;
      for (int f : star[static_cast<std::size_t>(v)]) {
        const Triangle& t = m.faces[static_cast<std::size_t>(f)];
        const int c = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
        sum += m.vertices[static_cast<std::size_t>(t[(c + 1) % 3])];
        ++n;
      }
      next[i] = pos[i] + 0.5 * (sum / n - pos[i]);
    }
    pos = std::move(next);
    for (std::size_t i = 0; i < movable.size(); ++i) m.vertices[static_cast<std::size_t>(movable[i])] = pos[i];
  }
  return pos;
}

//! The link of p: its neighbours in cyclic order (each face (p, q, r) gives
//! q before r); empty if the faces around p are not one disc.
std::vector<int> link_cycle(const Mesh& mesh, const std::vector<int>& star_p, int p) {
  std::vector<std::pair<int, int>> next;
  for (int f : star_p) {
    const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
    const int c = t[0] == p ? 0 : (t[1] == p ? 1 : 2);
    next.emplace_back(t[(c + 1) % 3], t[(c + 2) % 3]);
  }
  std::vector<int> cycle;
  int v = next.empty() ? -1 : next.front().first;
  for (std::size_t i = 0; i < next.size(); ++i) {
    cycle.push_back(v);
    const auto it = std::find_if(next.begin(), next.end(), [&](const auto& e) { return e.first == v; });
    if (it == next.end()) return {};
    v = it->second;
  }
  if (next.empty() || v != cycle.front()) return {};
  return cycle;
}

//! Chamfers a sharp ridge at vertex p (thesis 4.3.5: a fillet of one strip,
//! made at the vertex where no axis sees the two sides together): the faces
//! around p from link vertex a = cycle[i] to b = cycle[j] keep p, moved to
//! x1; the others get a new vertex at x2; two new faces (a, p, p') and
//! (b, p', p) join them. Each side's star can then face one of its own axes
//! and the strip faces one axis of each side. Both points keep p's reference
//! (the strip maps onto the ridge edges a-p and p-b), so the deviation bound
//! is max(|x1 - ref|, |x2 - ref|). Returns false (w unchanged) when a face
//! around p would flip or degenerate.
bool chamfer_vertex(RepairWork& w, const std::vector<int>& star_p, int p, const std::vector<int>& cycle, std::size_t i,
                    std::size_t j, const Vec3& x1, const Vec3& x2) {
  const std::size_t n = cycle.size();
  std::vector<char> first_side(w.mesh.vertices.size(), 0);
  for (std::size_t k = i; k != j; k = (k + 1) % n) first_side[static_cast<std::size_t>(cycle[k])] = 1;
  std::vector<Vec3> before;
  for (int f : star_p) before.push_back(face_normal_scaled(w.mesh, static_cast<std::size_t>(f)));
  RepairWork c = w;
  const int p2 = static_cast<int>(c.mesh.vertices.size());
  c.mesh.vertices.push_back(x2);
  c.reference.vertices.push_back(c.reference.vertices[static_cast<std::size_t>(p)]);
  c.mesh.vertices[static_cast<std::size_t>(p)] = x1;
  for (int f : star_p) {
    Triangle& t = c.mesh.faces[static_cast<std::size_t>(f)];
    const int k = t[0] == p ? 0 : (t[1] == p ? 1 : 2);
    if (!first_side[static_cast<std::size_t>(t[(k + 1) % 3])]) t[k] = p2;  // its link edge starts on the other side
  }
  c.mesh.faces.push_back({cycle[i], p, p2});
  c.mesh.faces.push_back({cycle[j], p2, p});
  c.reference.faces = c.mesh.faces;
  for (std::size_t k = 0; k < star_p.size(); ++k) {
    const Vec3 nk = face_normal_scaled(c.mesh, static_cast<std::size_t>(star_p[k]));
    if (!turns_less_than_75_degrees(before[k], nk)) return false;
  }
  for (std::size_t f = c.mesh.faces.size() - 2; f < c.mesh.faces.size(); ++f)
    if (!(face_normal_scaled(c.mesh, f).squaredNorm() > 0)) return false;
  w = std::move(c);
  return true;
}

//! Vertices of the faces an edit changed, before (`old`) or after (`now`) it:
//! faces with other vertex ids or a moved vertex, and the appended faces (the
//! edits only append vertices and faces). Only their corners and edges can
//! have changed feasibility.
std::vector<int> edited_region(const Mesh& old, const Mesh& now) {
  std::vector<char> moved(now.vertices.size(), 1);
  for (std::size_t v = 0; v < old.vertices.size(); ++v) moved[v] = old.vertices[v] != now.vertices[v];
  std::vector<int> region;
  for (std::size_t f = 0; f < now.faces.size(); ++f) {
    const Triangle& t = now.faces[f];
    const bool changed = f >= old.faces.size() || t != old.faces[f] ||
                         std::any_of(t.begin(), t.end(), [&](int v) { return moved[static_cast<std::size_t>(v)] != 0; });
    if (!changed) continue;
    region.insert(region.end(), t.begin(), t.end());
    if (f < old.faces.size()) region.insert(region.end(), old.faces[f].begin(), old.faces[f].end());
  }
  std::sort(region.begin(), region.end());
  region.erase(std::unique(region.begin(), region.end()), region.end());
  return region;
}

//! Does the edit from `old` to `now` leave strictly fewer infeasible
//! features? Decided by the exact test on the edited region only (the rest of
//! the surface is unchanged, so the difference of the local counts is the
//! difference of the whole mesh's).
bool has_fewer_features(const Mesh& old, const Mesh& now) {
  const std::vector<int> region = edited_region(old, now);
  if (region.empty()) return false;
  std::vector<int> old_region;
  for (int v : region)
    if (static_cast<std::size_t>(v) < old.vertices.size()) old_region.push_back(v);
  if (old_region.empty()) return false;  // only new faces: nothing was infeasible here
  const std::size_t before = find_infeasible_features(old, FeasibilityOptions{.only_vertices = old_region}).size();
  return before > 0 && find_infeasible_features(now, FeasibilityOptions{.only_vertices = region}).size() < before;
}

}  // namespace

std::vector<std::vector<int>> vertex_stars(const Mesh& mesh) {
  std::vector<std::vector<int>> star(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int v : mesh.faces[f]) star[static_cast<std::size_t>(v)].push_back(static_cast<int>(f));
  return star;
}

std::vector<int> ring_vertices(const Mesh& mesh, const std::vector<std::vector<int>>& star, int v, int rings) {
  std::vector<int> out{v};
  std::vector<char> seen(mesh.vertices.size(), 0);
  seen[static_cast<std::size_t>(v)] = 1;
  std::size_t begin = 0;
  for (int r = 0; r < rings; ++r) {
    const std::size_t end = out.size();
    std::vector<int> next;
    for (std::size_t i = begin; i < end; ++i)
      for (int f : star[static_cast<std::size_t>(out[i])])
        for (int u : mesh.faces[static_cast<std::size_t>(f)])
          if (!seen[static_cast<std::size_t>(u)]) {
            seen[static_cast<std::size_t>(u)] = 1;
            next.push_back(u);
          }
    std::sort(next.begin(), next.end());
    out.insert(out.end(), next.begin(), next.end());
    begin = end;
  }
  return out;
}

bool fix_infeasible_feature(RepairWork& w, const InfeasibleFeature& feature, FeasibilityResult& features, double cap,
                            LocalEdits edits) {
  const std::size_t before = features.size();
  const auto accept = [&](RepairWork& candidate) {
    if (!has_fewer_features(w.mesh, candidate.mesh)) return false;
    FeasibilityResult r = find_infeasible_features(candidate.mesh);
    if (r.size() >= before) return false;  // cannot happen (the local counts are exact); kept as a guard
    features = std::move(r);
    w = std::move(candidate);
    return true;
  };
  // 1. Split the corners at the vertex along the coordinate planes (no deviation).
  if (feature.kind == InfeasibleFeature::Kind::Vertex && feature.splittable) {
    RepairWork c = w;
    if (split_along_planes(c, feature.vertex0) && accept(c)) return true;
  }
  const std::vector<std::vector<int>> star = vertex_stars(w.mesh);
  std::vector<int> centres{feature.vertex0};
  if (feature.vertex1 >= 0) centres.push_back(feature.vertex1);
  // 2. Move one vertex: a feature vertex, then a neighbour.
  std::vector<int> movers = centres;
  for (int v : centres) {
    const std::vector<int> ring = ring_vertices(w.mesh, star, v, 1);
    for (int u : ring)
      if (std::find(movers.begin(), movers.end(), u) == movers.end()) movers.push_back(u);
  }
  for (int v : movers)
    for (const Vec3& x : move_candidates(w.mesh, star, v)) {
      RepairWork c = w;
      if (move_vertices(c, star, {v}, {x}, cap) && accept(c)) return true;
    }
  // 3. Smooth a small disc around the feature, its border fixed.
  for (int rings = 1; rings <= 3; ++rings)
    for (int steps : {2, 8}) {
      std::vector<int> movable;
      for (int v : centres)
        for (int u : ring_vertices(w.mesh, star, v, rings - 1))
          if (std::find(movable.begin(), movable.end(), u) == movable.end()) movable.push_back(u);
      const std::vector<Vec3> positions = smoothed_ring(w.mesh, star, movable, steps * rings);
      RepairWork c = w;
      if (move_vertices(c, star, movable, positions, cap) && accept(c)) return true;
    }
  // 4. Chamfer the ridge at a feature vertex: split its faces into two sides
  //    (at link vertices a, b not adjacent in the link) and join them with a
  //    strip, the two copies of the vertex moved a small fraction of the way
  //    into their sides (smallest first).
  if (edits != LocalEdits::WithRidgeChamfer) return false;
  for (int p : centres) {
    const std::vector<int>& star_p = star[static_cast<std::size_t>(p)];
    const std::vector<int> cycle = link_cycle(w.mesh, star_p, p);
    const std::size_t n = cycle.size();
    if (n < 4) continue;
    const Vec3 pp = w.mesh.vertices[static_cast<std::size_t>(p)];
    const Vec3 ref = w.reference.vertices[static_cast<std::size_t>(p)];
    for (double t : {0.03125, 0.125, 0.5})
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = (i + 2) % n; (j + 1) % n != i; j = (j + 1) % n) {
          Vec3 m1 = Vec3::Zero(), m2 = Vec3::Zero();  // centroids of each side's inner link vertices
          for (std::size_t k = (i + 1) % n; k != j; k = (k + 1) % n) m1 += w.mesh.vertices[static_cast<std::size_t>(cycle[k])];
          for (std::size_t k = (j + 1) % n; k != i; k = (k + 1) % n) m2 += w.mesh.vertices[static_cast<std::size_t>(cycle[k])];
          m1 /= static_cast<double>((j + n - i) % n - 1);
          m2 /= static_cast<double>((i + n - j) % n - 1);
          const Vec3 x1 = pp + t * (m1 - pp), x2 = pp + t * (m2 - pp);
          if (!((x1 - ref).norm() <= cap && (x2 - ref).norm() <= cap)) continue;
          RepairWork c = w;
          if (chamfer_vertex(c, star_p, p, cycle, i, j, x1, x2) && accept(c)) return true;
        }
  }
  return false;
}

}  // namespace subfab::detail
