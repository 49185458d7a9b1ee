// SPDX-License-Identifier: GPL-3.0-or-later
//! \file merge_coplanar_neighbours.cpp
//! Clean-ups of facet deletion (thesis Section 3.3.2) on an ExactPolyMesh:
//! merging adjacent facets on one plane (re-tracing their loops), removing
//! vertices where only two facets meet, and the check that no coplanar
//! neighbours are left.
#include "unfold/merge_coplanar_neighbours.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <unordered_map>

#include "unfold/edge_key.h"

namespace subfab::unfold_detail {

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

}  // namespace subfab::unfold_detail
