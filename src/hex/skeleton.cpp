// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/skeleton.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "subfab/core/error.h"

namespace subfab {

std::size_t Skeleton::num_edges() const {
  std::size_t twice = 0;
  for (const auto& n : neighbors) twice += n.size();
  return twice / 2;
}

int Skeleton::add_node(const Vec3& p, double r) {
  points.push_back(p);
  radii.push_back(r);
  neighbors.emplace_back();
  return static_cast<int>(points.size()) - 1;
}

void Skeleton::add_edge(int a, int b) {
  if (a == b) return;
  auto& na = neighbors[static_cast<std::size_t>(a)];
  if (std::find(na.begin(), na.end(), b) != na.end()) return;
  na.push_back(b);
  neighbors[static_cast<std::size_t>(b)].push_back(a);
}

std::vector<SkeletonArc> skeleton_arcs(const Skeleton& skeleton) {
  const std::size_t n = skeleton.num_nodes();
  std::vector<SkeletonArc> arcs;
  // visited edges, as (min, max) pairs in a per-node list
  std::vector<std::vector<int>> used(n);
  auto edge_used = [&](int a, int b) {
    const auto& u = used[static_cast<std::size_t>(std::min(a, b))];
    return std::find(u.begin(), u.end(), std::max(a, b)) != u.end();
  };
  auto mark = [&](int a, int b) { used[static_cast<std::size_t>(std::min(a, b))].push_back(std::max(a, b)); };
  auto degree = [&](int v) { return skeleton.neighbors[static_cast<std::size_t>(v)].size(); };

  auto walk = [&](int start, int next) {
    SkeletonArc arc;
    arc.nodes = {start};
    int prev = start, cur = next;
    mark(prev, cur);
    while (true) {
      arc.nodes.push_back(cur);
      if (degree(cur) != 2 || cur == start) break;
      const auto& nb = skeleton.neighbors[static_cast<std::size_t>(cur)];
      const int nxt = nb[0] == prev ? nb[1] : nb[0];
      if (edge_used(cur, nxt)) break;
      mark(cur, nxt);
      prev = cur;
      cur = nxt;
    }
    return arc;
  };

  for (std::size_t v = 0; v < n; ++v) {
    if (degree(static_cast<int>(v)) == 2) continue;
    std::vector<int> nb = skeleton.neighbors[v];
    std::sort(nb.begin(), nb.end());
    for (int w : nb)
      if (!edge_used(static_cast<int>(v), w)) arcs.push_back(walk(static_cast<int>(v), w));
  }
  // pure cycles: every node of degree 2, none reached yet
  for (std::size_t v = 0; v < n; ++v) {
    if (degree(static_cast<int>(v)) != 2) continue;
    const auto& nb = skeleton.neighbors[v];
    if (edge_used(static_cast<int>(v), nb[0]) || edge_used(static_cast<int>(v), nb[1])) continue;
    SkeletonArc arc = walk(static_cast<int>(v), std::min(nb[0], nb[1]));
    arc.closed = true;
    arcs.push_back(std::move(arc));
  }
  return arcs;
}

double arc_length(const Skeleton& skeleton, const SkeletonArc& arc) {
  double length = 0;
  for (std::size_t i = 1; i < arc.nodes.size(); ++i)
    length += (skeleton.points[static_cast<std::size_t>(arc.nodes[i])] -
               skeleton.points[static_cast<std::size_t>(arc.nodes[i - 1])])
                  .norm();
  return length;
}

void check_skeleton(const Skeleton& skeleton) {
  const std::size_t n = skeleton.num_nodes();
  if (skeleton.radii.size() != n || skeleton.neighbors.size() != n)
    throw InvalidArgumentError("skeleton: points, radii and neighbour lists differ in size");
  for (std::size_t v = 0; v < n; ++v) {
    const std::string where = "skeleton node " + std::to_string(v) + ": ";
    if (!skeleton.points[v].allFinite()) throw InvalidArgumentError(where + "non-finite coordinates");
    if (!(skeleton.radii[v] > 0) || !std::isfinite(skeleton.radii[v]))
      throw InvalidArgumentError(where + "radius must be positive and finite");
    const auto& nb = skeleton.neighbors[v];
    for (std::size_t i = 0; i < nb.size(); ++i) {
      const int w = nb[i];
      if (w < 0 || static_cast<std::size_t>(w) >= n)
        throw InvalidArgumentError(where + "neighbour " + std::to_string(w) + " out of range [0, " +
                                   std::to_string(n) + ")");
      if (static_cast<std::size_t>(w) == v) throw InvalidArgumentError(where + "is its own neighbour");
      if (std::find(nb.begin(), nb.begin() + static_cast<std::ptrdiff_t>(i), w) != nb.begin() + static_cast<std::ptrdiff_t>(i))
        throw InvalidArgumentError(where + "neighbour " + std::to_string(w) + " listed twice");
      const auto& back = skeleton.neighbors[static_cast<std::size_t>(w)];
      if (std::find(back.begin(), back.end(), static_cast<int>(v)) == back.end())
        throw InvalidArgumentError(where + "lists " + std::to_string(w) + " as a neighbour but node " +
                                   std::to_string(w) + " does not list it back");
    }
  }
}

std::size_t num_skeleton_components(const Skeleton& skeleton) {
  const std::size_t n = skeleton.num_nodes();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x) x = parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    return x;
  };
  for (std::size_t v = 0; v < n; ++v)
    for (int w : skeleton.neighbors[v]) parent[static_cast<std::size_t>(find(static_cast<int>(v)))] = find(w);
  std::size_t count = 0;
  for (std::size_t v = 0; v < n; ++v) count += find(static_cast<int>(v)) == static_cast<int>(v);
  return count;
}

}  // namespace subfab
