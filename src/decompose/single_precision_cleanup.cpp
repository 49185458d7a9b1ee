// SPDX-License-Identifier: GPL-3.0-or-later
#include "decompose/single_precision_cleanup.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "geometry/clip_solid_to_box.h"
#include "geometry/deterministic_arena.h"
#include "geometry/exact_mesh.h"
#include "geometry/solid_index.h"
#include "subfab/checks/check_self_intersections.h"
#include "subfab/mesh/float32.h"
#include "subfab/validate/check_single_precision.h"
#include "validate/validate_booleans.h"

namespace subfab::detail {
namespace {

//! The float on the other side of x from its rounding (x between them).
double other_float(double x) {
  const double rounded = round_to_float32(x);  // not a bare cast: see float32.h
  if (rounded == x) return x;
  const float f = static_cast<float>(rounded);  // exact
  return round_to_float32(static_cast<double>(
      std::nextafter(f, rounded < x ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity())));
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

//! Snaps, per machine axis, the coordinates of `machine` that lie within
//! `gap` of each other (clusters no wider than `gap`) to the cluster's most
//! used value (ties: the lowest), and moves the same vertices of `block` by
//! the same displacement taken back to its frame (`to_machine`^T). Returns
//! the number of coordinates moved.
std::size_t snap_to_planes(Mesh& machine, Mesh& block, const Eigen::Matrix3d& to_machine, double gap) {
  std::size_t moved = 0;
  std::vector<Vec3> delta(machine.num_vertices(), Vec3::Zero());
  for (int k = 0; k < 3; ++k) {
    std::map<double, std::size_t> count;
    for (const Vec3& v : machine.vertices) ++count[v[k]];
    std::map<double, double> to;  // value -> snapped value
    for (auto it = count.begin(); it != count.end();) {
      auto end = it;
      double best = it->first;
      std::size_t most = 0;
      while (end != count.end() && end->first - it->first <= gap) {
        if (end->second > most) {
          most = end->second;
          best = end->first;
        }
        ++end;
      }
      for (auto c = it; c != end; ++c) to[c->first] = best;
      it = end;
    }
    for (std::size_t v = 0; v < machine.num_vertices(); ++v) {
      const double target = to[machine.vertices[v][k]];
      if (target == machine.vertices[v][k]) continue;
      delta[v][k] = target - machine.vertices[v][k];
      machine.vertices[v][k] = target;
      ++moved;
    }
  }
  for (std::size_t v = 0; v < machine.num_vertices(); ++v)
    if (delta[v] != Vec3::Zero()) block.vertices[v] += to_machine.transpose() * delta[v];
  return moved;
}

//! Removes the zero-area faces of `machine` whose three corners are distinct
//! and collinear (a needle flattened by a snap): the corner m lying on the
//! opposite edge (a, b) splits the face across that edge into two, and the
//! needle goes (when the face across is the needle's own twin, both go).
//! Skipped where the split would duplicate an edge. The same changes apply
//! to `block` (same vertex ids). Returns the number of needles removed.
std::size_t split_needles(Mesh& machine, Mesh& block, SinglePrecisionCleanup& r) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  const auto point = [&](int v) {
    const Vec3& p = machine.vertices[static_cast<std::size_t>(v)];
    return K::Point_3(p.x(), p.y(), p.z());
  };
  std::size_t removed = 0;
  for (int pass = 0; pass < 64; ++pass) {
    std::map<std::pair<int, int>, std::size_t> edge_face;  // directed edge -> face
    std::set<std::pair<int, int>> undirected;
    for (std::size_t f = 0; f < machine.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int a = machine.faces[f][k], b = machine.faces[f][(k + 1) % 3];
        edge_face[{a, b}] = f;
        undirected.insert({std::min(a, b), std::max(a, b)});
      }
    std::vector<char> gone(machine.num_faces(), 0);
    std::vector<Triangle> added;
    std::set<int> touched;
    for (std::size_t f = 0; f < machine.num_faces(); ++f) {
      const Triangle t = machine.faces[f];
      if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;
      if (!CGAL::collinear(point(t[0]), point(t[1]), point(t[2]))) continue;
      if (touched.count(t[0]) || touched.count(t[1]) || touched.count(t[2])) continue;
      // the corner between the other two
      int i = -1;
      for (int k = 0; k < 3 && i < 0; ++k)
        if (CGAL::collinear_are_strictly_ordered_along_line(point(t[(k + 1) % 3]), point(t[k]), point(t[(k + 2) % 3])))
          i = k;
      if (i < 0) continue;  // two corners coincide: left to the weld
      const int m = t[i], a = t[(i + 1) % 3], b = t[(i + 2) % 3];
      const auto across = edge_face.find({b, a});
      if (across == edge_face.end() || gone[across->second]) continue;
      const Triangle g = machine.faces[across->second];
      int d = -1;
      for (int w : g)
        if (w != a && w != b) d = w;
      if (touched.count(d)) continue;
      if (d == m) {  // the needle's twin: both go
        gone[f] = gone[across->second] = 1;
      } else {
        if (undirected.count({std::min(m, d), std::max(m, d)})) continue;
        gone[f] = gone[across->second] = 1;
        added.push_back({b, m, d});
        added.push_back({m, a, d});
        undirected.insert({std::min(m, d), std::max(m, d)});
      }
      for (int w : {m, a, b, d}) touched.insert(w);
      ++removed;
    }
    if (touched.empty()) break;
    std::vector<Triangle> faces;
    for (std::size_t f = 0; f < machine.num_faces(); ++f)
      if (!gone[f]) faces.push_back(machine.faces[f]);
    faces.insert(faces.end(), added.begin(), added.end());
    machine.faces = std::move(faces);
  }
  if (removed == 0) return 0;
  r.num_faces_removed += removed;
  block.faces = machine.faces;
  remove_unreferenced_vertices(block);
  remove_unreferenced_vertices(machine);
  return removed;
}

//! `machine` clipped, exactly, to the box that leaves out the sub-float
//! slabs at its extremes: along each axis, when its coordinates within
//! `gap` of its largest (smallest) one take more than one value, the part
//! above the lowest (below the highest) of them goes (a fin thinner than a
//! float on the block's side). Nullopt when there is no such slab, or the
//! clip is not one closed piece.
std::optional<Mesh> clip_extreme_slabs(const Mesh& machine, double gap) {
  const BoundingBox box = bounding_box(machine);
  Box3 keep{box.min.array() - 1.0, box.max.array() + 1.0};
  bool any = false;
  for (int k = 0; k < 3; ++k) {
    std::set<double> values;
    for (const Vec3& v : machine.vertices) values.insert(v[k]);
    double top = box.max[k], bottom = box.min[k];
    for (double x : values) {
      if (x >= box.max[k] - gap) top = std::min(top, x);
      if (x <= box.min[k] + gap) bottom = std::max(bottom, x);
    }
    if (top < box.max[k] && top > box.min[k]) {
      keep.max[k] = top;
      any = true;
    }
    if (bottom > box.min[k] && bottom < keep.max[k]) {
      keep.min[k] = bottom;
      any = true;
    }
  }
  if (!any) return std::nullopt;
  // CGAL's corefinement may crash (not throw) on a mesh the exact booleans
  // refuse (self-intersections, zero-area faces): not clipped then.
  if (!boolean_input_defect(machine, true).empty()) return std::nullopt;
  std::optional<Mesh> out;
  warm_up_exact_booleans();
  const SolidIndex index(machine);
  run_in_arena([&] {
    std::vector<ExactMesh> pieces = clip_solid_to_box(machine, index, keep);
    if (pieces.size() != 1) return;
    SuspendArena heap;
    RoundingReport rounding;
    Mesh m = to_double(pieces.front(), &rounding);
    if (rounding.num_degenerate_faces + rounding.num_flipped_faces == 0) out = std::move(m);
  });
  return out;
}

//! Removes the vertices of `machine` with exactly three faces that lie in
//! one plane (a bump a few floats high, flattened by a snap: its faces may
//! fold over each other): the three faces become the one triangle of their
//! outer edges. Skipped where that triangle exists already. The same changes
//! apply to `block`. Returns the number of vertices removed.
std::size_t remove_flat_tips(Mesh& machine, Mesh& block, SinglePrecisionCleanup& r) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  const auto point = [&](int v) {
    const Vec3& p = machine.vertices[static_cast<std::size_t>(v)];
    return K::Point_3(p.x(), p.y(), p.z());
  };
  std::vector<std::vector<std::size_t>> faces_of(machine.num_vertices());
  std::set<std::array<int, 3>> existing;
  for (std::size_t f = 0; f < machine.num_faces(); ++f) {
    for (int v : machine.faces[f]) faces_of[static_cast<std::size_t>(v)].push_back(f);
    std::array<int, 3> key{machine.faces[f][0], machine.faces[f][1], machine.faces[f][2]};
    std::sort(key.begin(), key.end());
    existing.insert(key);
  }
  std::vector<char> gone(machine.num_faces(), 0);
  std::vector<Triangle> added;
  std::size_t removed = 0;
  for (std::size_t v = 0; v < machine.num_vertices(); ++v) {
    const std::vector<std::size_t>& fs = faces_of[v];
    if (fs.size() != 3 || gone[fs[0]] || gone[fs[1]] || gone[fs[2]]) continue;
    std::map<int, int> next;  // outer edge x -> y of each face (v, x, y)
    for (std::size_t f : fs) {
      const Triangle& t = machine.faces[f];
      const int k = t[0] == static_cast<int>(v) ? 0 : t[1] == static_cast<int>(v) ? 1 : 2;
      next[t[(k + 1) % 3]] = t[(k + 2) % 3];
    }
    if (next.size() != 3) continue;
    const int a = next.begin()->first, b = next[a], c = next.count(b) ? next[b] : -1;
    if (c < 0 || !next.count(c) || next[c] != a) continue;
    if (!CGAL::coplanar(point(static_cast<int>(v)), point(a), point(b), point(c)) ||
        CGAL::collinear(point(a), point(b), point(c)))
      continue;
    std::array<int, 3> key{a, b, c};
    std::sort(key.begin(), key.end());
    if (existing.count(key)) continue;
    existing.insert(key);
    for (std::size_t f : fs) gone[f] = 1;
    added.push_back({a, b, c});
    ++removed;
  }
  if (removed == 0) return 0;
  std::vector<Triangle> faces;
  for (std::size_t f = 0; f < machine.num_faces(); ++f)
    if (!gone[f]) faces.push_back(machine.faces[f]);
  faces.insert(faces.end(), added.begin(), added.end());
  machine.faces = std::move(faces);
  block.faces = machine.faces;
  remove_unreferenced_vertices(block);
  remove_unreferenced_vertices(machine);
  r.num_collapsed += removed;
  r.num_faces_removed += 2 * removed;
  return removed;
}

//! Rounds `machine` to float32 and repairs what the rounding broke (see
//! clean_single_precision()).
void round_and_repair(Mesh& machine, Mesh& block, SinglePrecisionCleanup& r) {
  std::vector<Vec3> exact = machine.vertices;  // before rounding, for the other rounding
  for (Vec3& v : machine.vertices) v = round_to_float32(v);
  collapse(machine, block, r);
  if (r.num_collapsed > 0) exact = machine.vertices;  // ids changed: nudge from the floats
  // A needle only rounding flattens (its corners distinct, collinear in
  // floats: a sliver triangle of a base polygon's triangulation, bimba at
  // 7.5e-3) is split across its long edge, in the float coordinates.
  const std::size_t num_vertices = machine.num_vertices();
  if (split_needles(machine, block, r) > 0 && machine.num_vertices() != num_vertices) exact = machine.vertices;
  // Nudge the vertices of crossing faces, at most 3 passes.
  for (int pass = 0; pass < 3; ++pass) {
    const CheckResult crossing = check_self_intersections(machine, {.max_examples = 64});
    if (crossing.num_offending == 0) break;
    std::set<int> vertices;
    for (int f : crossing.examples)
      for (int v : machine.faces[static_cast<std::size_t>(f)]) vertices.insert(v);
    // Moving v changes only the pairs that hold a face around v: each
    // candidate's count is the others' (fixed while v moves) plus those.
    std::vector<std::vector<int>> around(machine.num_vertices());
    for (std::size_t f = 0; f < machine.num_faces(); ++f)
      for (const int w : machine.faces[f])
        if (vertices.count(w) && (around[static_cast<std::size_t>(w)].empty() ||
                                  around[static_cast<std::size_t>(w)].back() != static_cast<int>(f)))
          around[static_cast<std::size_t>(w)].push_back(static_cast<int>(f));
    std::size_t best = crossing.num_offending;  // the count now (with the kept moves)
    for (int v : vertices) {
      const std::size_t vs = static_cast<std::size_t>(v);
      const std::vector<int>& star = around[vs];
      const std::size_t others = best - count_self_intersections_of(machine, star);
      const Vec3 rounded = machine.vertices[vs], other(other_float(exact[vs].x()), other_float(exact[vs].y()),
                                                       other_float(exact[vs].z()));
      Vec3 keep = rounded;
      for (int mask = 1; mask < 8; ++mask) {
        Vec3 candidate = rounded;
        for (int k = 0; k < 3; ++k)
          if (mask & (1 << k)) candidate[k] = other[k];
        if (candidate == rounded) continue;
        machine.vertices[vs] = candidate;
        const std::size_t count = others + count_self_intersections_of(machine, star);
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

SinglePrecisionCleanup clean_single_precision(Mesh& machine, Mesh& block, const Eigen::Matrix3d* to_machine,
                                              const std::function<bool(const Mesh&)>& block_valid) {
  // A repair must keep the block (in doubles) valid too: merging a vertex
  // into its float twin moves it in `block` as well, which can fold a face
  // smaller than a float (couplingdown.off at 1e-3, block 049: one face of
  // its top plane turned over).
  const auto accepted = [&](SinglePrecisionCleanup& c, const Mesh& b) {
    if (c.ok && block_valid && !block_valid(b)) {
      c.ok = false;
      c.block_invalid = true;
    }
    return c.ok;
  };
  SinglePrecisionCleanup r;
  if (check_single_precision(machine).ok()) return r;
  const Mesh machine_before = machine, block_before = block;
  round_and_repair(machine, block, r);
  if (accepted(r, block)) return r;
  // Clusters of vertices closer than a few float spacings: collapse their
  // edges first (in double), then round again; kept when that gives a solid.
  const double magnitude = largest_coordinate(machine_before);
  const double spacing = magnitude * std::ldexp(1.0, -23);  // float32's spacing at the largest coordinate (upper bound)
  SinglePrecisionCleanup again;
  Mesh machine2 = machine_before, block2 = block_before;
  if (collapse_short_edges(machine2, block2, 4 * spacing, again) > 0) {
    round_and_repair(machine2, block2, again);
    if (accepted(again, block2)) {
      machine = std::move(machine2);
      block = std::move(block2);
      return again;
    }
  }
  // Coordinates a few float spacings off a plane of the block (CAD noise:
  // vertices 1e-10 to 1e-8 off the plane of their neighbours; a box plane
  // through one of them cuts a sub-float fin or needle faces): snap them
  // onto the plane first, weld, split the needles, then round.
  if (!to_machine) return r;
  const auto snap_and_round = [&](Mesh& m, Mesh& b, SinglePrecisionCleanup& c) {
    snap_to_planes(m, b, *to_machine, 4 * spacing);
    for (int pass = 0; pass < 4; ++pass) {
      const std::size_t before = c.num_collapsed + c.num_faces_removed;
      collapse(m, b, c);
      split_needles(m, b, c);
      remove_flat_tips(m, b, c);
      collapse_short_edges(m, b, 0.5 * spacing, c);
      if (c.num_collapsed + c.num_faces_removed == before) break;
    }
    round_and_repair(m, b, c);
    return c.ok;
  };
  SinglePrecisionCleanup snapped;
  Mesh machine3 = machine_before, block3 = block_before;
  if (snap_and_round(machine3, block3, snapped) && accepted(snapped, block3)) {
    machine = std::move(machine3);
    block = std::move(block3);
    return snapped;
  }
  // A fin thinner than a float on a side of the block (a box plane through
  // a noisy vertex): snapping flattens it into two coincident layers; clip
  // it off exactly instead (in machine coordinates; the block is the clipped
  // mesh moved back), then snap and round.
  std::optional<Mesh> clipped = clip_extreme_slabs(machine_before, 4 * spacing);
  if (!clipped) return r;
  const Vec3 shift = machine_before.vertices.front() - *to_machine * block_before.vertices.front();
  Mesh block4 = *clipped;
  for (Vec3& v : block4.vertices) v = to_machine->transpose() * (v - shift);
  SinglePrecisionCleanup fin;
  fin.num_faces_removed = machine_before.num_faces();  // counted as replaced
  if (!snap_and_round(*clipped, block4, fin) || !accepted(fin, block4)) return r;
  machine = std::move(*clipped);
  block = std::move(block4);
  return fin;
}

SinglePrecisionCleanup clean_block_for_stl(Mesh& machine, Mesh& block, const Eigen::Matrix3d& to_machine,
                                           const Vec3& direction, double diagonal, const FinalizeOptions& options) {
  return clean_single_precision(machine, block, &to_machine, [&](const Mesh& b) {
    return block_defect(b, direction, diagonal, options).empty();
  });
}

}  // namespace subfab::detail
