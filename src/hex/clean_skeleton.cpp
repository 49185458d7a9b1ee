// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/clean_skeleton.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace subfab {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

void remove_neighbor(Skeleton& g, int v, int w) {
  auto& nb = g.neighbors[idx(v)];
  nb.erase(std::remove(nb.begin(), nb.end(), w), nb.end());
}

//! Node b disappears into a: its edges move to a (no self-loop, no duplicate).
void merge_into(Skeleton& g, int a, int b) {
  const std::vector<int> nb = g.neighbors[idx(b)];
  for (int w : nb) {
    remove_neighbor(g, w, b);
    if (w != a) g.add_edge(a, w);
  }
  g.neighbors[idx(b)].clear();
}

//! Removes every edge of v (v becomes an isolated, dead node).
void isolate(Skeleton& g, int v) {
  for (int w : g.neighbors[idx(v)]) remove_neighbor(g, w, v);
  g.neighbors[idx(v)].clear();
}

std::size_t degree(const Skeleton& g, int v) { return g.neighbors[idx(v)].size(); }

//! Collapses the arc between two branching nodes whose spheres overlap the
//! most (relative to their distance); false when there is none.
bool collapse_one(Skeleton& g) {
  const auto arcs = skeleton_arcs(g);
  int best = -1;
  double best_ratio = 1.0;
  for (std::size_t i = 0; i < arcs.size(); ++i) {
    const auto& arc = arcs[i];
    const int a = arc.nodes.front(), b = arc.nodes.back();
    if (a == b || degree(g, a) < 3 || degree(g, b) < 3) continue;
    const double d = (g.points[idx(a)] - g.points[idx(b)]).norm();
    const double ratio = (g.radii[idx(a)] + g.radii[idx(b)]) / std::max(d, 1e-300);
    if (ratio <= best_ratio) continue;
    // would another arc between a and b become a cycle of fewer than 3 nodes?
    bool unsafe = false;
    for (std::size_t j = 0; j < arcs.size() && !unsafe; ++j) {
      if (j == i) continue;
      const auto& other = arcs[j];
      const bool same_ends = (other.nodes.front() == a && other.nodes.back() == b) ||
                             (other.nodes.front() == b && other.nodes.back() == a);
      if (same_ends && other.nodes.size() < 4) unsafe = true;
    }
    if (unsafe) continue;
    best = static_cast<int>(i);
    best_ratio = ratio;
  }
  if (best < 0) return false;
  const auto& arc = arcs[idx(best)];
  const int a = std::min(arc.nodes.front(), arc.nodes.back());
  const int b = std::max(arc.nodes.front(), arc.nodes.back());
  const double ra = g.radii[idx(a)], rb = g.radii[idx(b)];
  const Vec3 p = (ra * g.points[idx(a)] + rb * g.points[idx(b)]) / (ra + rb);
  for (int v : arc.nodes)
    if (v != a) merge_into(g, a, v);
  g.points[idx(a)] = p;
  g.radii[idx(a)] = std::max(ra, rb);
  return true;
}

//! Removes the shortest (relative to its branching node's radius) terminal
//! arc under the threshold; false when there is none.
bool prune_one(Skeleton& g, double factor) {
  const auto arcs = skeleton_arcs(g);
  int best = -1;
  double best_ratio = factor;
  for (std::size_t i = 0; i < arcs.size(); ++i) {
    const auto& arc = arcs[i];
    const int a = arc.nodes.front(), b = arc.nodes.back();
    int junction;
    if (degree(g, a) == 1 && degree(g, b) >= 3)
      junction = b;
    else if (degree(g, b) == 1 && degree(g, a) >= 3)
      junction = a;
    else
      continue;
    const double ratio = arc_length(g, arc) / g.radii[idx(junction)];
    if (ratio < best_ratio) {
      best_ratio = ratio;
      best = static_cast<int>(i);
    }
  }
  if (best < 0) return false;
  const auto& arc = arcs[idx(best)];
  const int junction = degree(g, arc.nodes.front()) >= 3 ? arc.nodes.front() : arc.nodes.back();
  for (int v : arc.nodes)
    if (v != junction) isolate(g, v);
  return true;
}

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

std::size_t drop_redundant(Skeleton& g, double tolerance) {
  std::size_t dropped = 0;
  for (std::size_t v = 0; v < g.num_nodes(); ++v) {
    if (g.neighbors[v].size() != 2) continue;
    const int a = g.neighbors[v][0], b = g.neighbors[v][1];
    const auto& na = g.neighbors[idx(a)];
    if (std::find(na.begin(), na.end(), b) != na.end()) continue;  // keep triangles
    if (distance_to_segment(g.points[v], g.points[idx(a)], g.points[idx(b)]) >= tolerance * g.radii[v]) continue;
    isolate(g, static_cast<int>(v));
    g.add_edge(a, b);
    ++dropped;
  }
  return dropped;
}

}  // namespace

Skeleton clean_skeleton(const Skeleton& skeleton, const CleanSkeletonOptions& options, CleanSkeletonReport* report) {
  Skeleton g = skeleton;
  CleanSkeletonReport r;
  while (true) {
    if (collapse_one(g)) {
      ++r.branches_collapsed;
      continue;
    }
    if (prune_one(g, options.prune_factor)) {
      ++r.branches_pruned;
      continue;
    }
    break;
  }
  // isolated nodes left by the merges and prunes are dead (a skeleton that
  // was a single node keeps it)
  r.nodes_dropped = drop_redundant(g, options.collinear_tolerance);
  std::vector<int> new_index(g.num_nodes(), -1);
  Skeleton out;
  const bool keep_isolated = g.num_edges() == 0;
  for (std::size_t v = 0; v < g.num_nodes(); ++v)
    if (!g.neighbors[v].empty() || (keep_isolated && skeleton.neighbors[v].empty()))
      new_index[v] = out.add_node(g.points[v], g.radii[v]);
  for (std::size_t v = 0; v < g.num_nodes(); ++v)
    for (int w : g.neighbors[v])
      if (new_index[v] >= 0 && new_index[idx(w)] >= 0) out.add_edge(new_index[v], new_index[idx(w)]);
  if (report) *report = r;
  return out;
}

}  // namespace subfab
