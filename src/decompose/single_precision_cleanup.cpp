// SPDX-License-Identifier: GPL-3.0-or-later
#include "decompose/single_precision_cleanup.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <vector>

#include "subfab/checks/check_self_intersections.h"
#include "subfab/validate/check_single_precision.h"

namespace subfab::detail {
namespace {

double to_float(double x) { return static_cast<double>(static_cast<float>(x)); }

//! The float on the other side of x from its rounding (x between them).
double other_float(double x) {
  const float f = static_cast<float>(x);
  if (static_cast<double>(f) == x) return x;
  return static_cast<double>(std::nextafter(f, static_cast<double>(f) < x ? std::numeric_limits<float>::infinity()
                                                                         : -std::numeric_limits<float>::infinity()));
}

//! Merges vertices of `machine` that are equal (already floats), applies the
//! same merge to `block`, and removes the faces that lost their area (a
//! repeated vertex) and coincident pairs of opposite faces.
void collapse(Mesh& machine, Mesh& block, SinglePrecisionCleanup& r) {
  std::map<std::array<double, 3>, int> first;
  std::vector<int> to(machine.num_vertices());
  for (std::size_t v = 0; v < machine.num_vertices(); ++v) {
    const Vec3& p = machine.vertices[v];
    const auto [it, added] = first.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, static_cast<int>(v));
    to[v] = it->second;
    if (!added) {
      ++r.num_collapsed;
      block.vertices[v] = block.vertices[static_cast<std::size_t>(it->second)];
    }
  }
  if (r.num_collapsed == 0) return;
  std::vector<Triangle> faces;
  std::map<std::array<int, 3>, std::size_t> seen;  // sorted corners -> index in faces
  std::vector<char> removed;
  for (Triangle f : machine.faces) {
    for (int& v : f) v = to[static_cast<std::size_t>(v)];
    if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) {
      ++r.num_faces_removed;
      continue;
    }
    std::array<int, 3> key{f[0], f[1], f[2]};
    std::sort(key.begin(), key.end());
    if (const auto it = seen.find(key); it != seen.end() && !removed[it->second]) {
      removed[it->second] = 1;  // the same triangle twice (a collapsed sheet's two sides): both go
      r.num_faces_removed += 2;
      continue;
    }
    seen[key] = faces.size();
    faces.push_back(f);
    removed.push_back(0);
  }
  machine.faces.clear();
  for (std::size_t k = 0; k < faces.size(); ++k)
    if (!removed[k]) machine.faces.push_back(faces[k]);
  block.faces = machine.faces;
  remove_unreferenced_vertices(block);  // same order as in machine: unreferenced ids are the same
  remove_unreferenced_vertices(machine);
}

std::size_t num_crossing(const Mesh& m) { return check_self_intersections(m, {.max_examples = 64}).num_offending; }

//! Collapses the edges of `machine` shorter than `length`, shortest first
//! (ties by vertex ids), each onto its lower-id end, when the collapse keeps
//! a closed 2-manifold: the two ends share exactly the two vertices opposite
//! the edge (the link condition) and more than four vertices remain. The
//! same collapses apply to `block` (same ids). Faces of the edge go; returns
//! the number of collapses. Sub-float clusters of vertices (box planes
//! cutting the surface within 1e-8 of each other) weld in float32 as a
//! whole; merging only the vertices that round to the same float point can
//! pinch the surface, collapsing edges cannot.
std::size_t collapse_short_edges(Mesh& machine, Mesh& block, double length, SinglePrecisionCleanup& r) {
  const std::size_t nv = machine.num_vertices();
  std::vector<std::vector<std::size_t>> faces_of(nv);
  std::vector<char> alive(machine.num_faces(), 1);
  for (std::size_t f = 0; f < machine.num_faces(); ++f)
    for (int v : machine.faces[f]) faces_of[static_cast<std::size_t>(v)].push_back(f);
  struct Edge {
    double length;
    int a, b;
    bool operator<(const Edge& o) const { return std::tie(length, a, b) < std::tie(o.length, o.a, o.b); }
  };
  std::vector<Edge> edges;
  for (const Triangle& t : machine.faces)
    for (int k = 0; k < 3; ++k) {
      const int a = std::min(t[k], t[(k + 1) % 3]), b = std::max(t[k], t[(k + 1) % 3]);
      const double l = (machine.vertices[static_cast<std::size_t>(a)] - machine.vertices[static_cast<std::size_t>(b)]).norm();
      if (l < length) edges.push_back({l, a, b});
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.a == y.a && x.b == y.b; }),
              edges.end());
  std::size_t remaining = 0;
  for (std::size_t v = 0; v < nv; ++v) remaining += faces_of[v].empty() ? 0 : 1;
  std::size_t collapsed = 0;
  const auto neighbours = [&](int v) {
    std::set<int> out;
    for (std::size_t f : faces_of[static_cast<std::size_t>(v)])
      if (alive[f])
        for (int w : machine.faces[f])
          if (w != v) out.insert(w);
    return out;
  };
  for (const Edge& e : edges) {
    if (remaining <= 4) break;
    // the faces holding both ends (none when an earlier collapse took the edge)
    std::vector<std::size_t> shared;
    std::set<int> opposite;
    for (std::size_t f : faces_of[static_cast<std::size_t>(e.a)]) {
      if (!alive[f]) continue;
      const Triangle& t = machine.faces[f];
      if (std::find(t.begin(), t.end(), e.b) == t.end()) continue;
      shared.push_back(f);
      for (int w : t)
        if (w != e.a && w != e.b) opposite.insert(w);
    }
    if (shared.size() != 2 || opposite.size() != 2) continue;
    const std::set<int> na = neighbours(e.a), nb = neighbours(e.b);
    std::vector<int> common;
    std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
    if (common.size() != 2) continue;  // link condition
    for (std::size_t f : shared) alive[f] = 0;
    for (std::size_t f : faces_of[static_cast<std::size_t>(e.b)]) {
      if (!alive[f]) continue;
      for (int& w : machine.faces[f])
        if (w == e.b) w = e.a;
      faces_of[static_cast<std::size_t>(e.a)].push_back(f);
    }
    faces_of[static_cast<std::size_t>(e.b)].clear();
    --remaining;
    ++collapsed;
    r.num_faces_removed += 2;
  }
  if (collapsed == 0) return 0;
  std::vector<Triangle> kept;
  for (std::size_t f = 0; f < machine.num_faces(); ++f)
    if (alive[f]) kept.push_back(machine.faces[f]);
  machine.faces = std::move(kept);
  block.faces = machine.faces;
  remove_unreferenced_vertices(block);  // same order as in machine: unreferenced ids are the same
  remove_unreferenced_vertices(machine);
  r.num_collapsed += collapsed;
  return collapsed;
}

//! Rounds `machine` to float32 and repairs what the rounding broke (see
//! clean_single_precision()).
void round_and_repair(Mesh& machine, Mesh& block, SinglePrecisionCleanup& r) {
  std::vector<Vec3> exact = machine.vertices;  // before rounding, for the other rounding
  for (Vec3& v : machine.vertices) v = Vec3(to_float(v.x()), to_float(v.y()), to_float(v.z()));
  collapse(machine, block, r);
  if (r.num_collapsed > 0) exact = machine.vertices;  // ids changed: nudge from the floats
  // Nudge the vertices of crossing faces, at most 3 passes.
  for (int pass = 0; pass < 3; ++pass) {
    const CheckResult crossing = check_self_intersections(machine, {.max_examples = 64});
    if (crossing.num_offending == 0) break;
    std::set<int> vertices;
    for (int f : crossing.examples)
      for (int v : machine.faces[static_cast<std::size_t>(f)]) vertices.insert(v);
    std::size_t best = crossing.num_offending;
    for (int v : vertices) {
      const std::size_t vs = static_cast<std::size_t>(v);
      const Vec3 rounded = machine.vertices[vs], other(other_float(exact[vs].x()), other_float(exact[vs].y()),
                                                       other_float(exact[vs].z()));
      Vec3 keep = rounded;
      for (int mask = 1; mask < 8; ++mask) {
        Vec3 candidate = rounded;
        for (int k = 0; k < 3; ++k)
          if (mask & (1 << k)) candidate[k] = other[k];
        if (candidate == rounded) continue;
        machine.vertices[vs] = candidate;
        const std::size_t count = num_crossing(machine);
        if (count < best) {
          best = count;
          keep = candidate;
        }
      }
      machine.vertices[vs] = keep;
      if (keep != rounded) ++r.num_nudged;
      if (best == 0) break;
    }
  }
  r.ok = check_single_precision(machine).ok();
}

}  // namespace

SinglePrecisionCleanup clean_single_precision(Mesh& machine, Mesh& block) {
  SinglePrecisionCleanup r;
  if (check_single_precision(machine).ok()) return r;
  const Mesh machine_before = machine, block_before = block;
  round_and_repair(machine, block, r);
  if (r.ok) return r;
  // Clusters of vertices closer than a few float spacings: collapse their
  // edges first (in double), then round again; kept when that gives a solid.
  double magnitude = 0;
  for (const Vec3& v : machine_before.vertices) magnitude = std::max(magnitude, v.cwiseAbs().maxCoeff());
  const double spacing = magnitude * std::ldexp(1.0, -23);  // float32's spacing at the largest coordinate (upper bound)
  SinglePrecisionCleanup again;
  Mesh machine2 = machine_before, block2 = block_before;
  if (collapse_short_edges(machine2, block2, 4 * spacing, again) == 0) return r;
  round_and_repair(machine2, block2, again);
  if (!again.ok) return r;
  machine = std::move(machine2);
  block = std::move(block2);
  return again;
}

}  // namespace subfab::detail
