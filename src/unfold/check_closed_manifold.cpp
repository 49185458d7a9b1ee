// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_closed_manifold.cpp
//! Exact closed-manifold check of facet deletion (thesis Section 3.3.2): every
//! directed edge of an ExactPolyMesh has exactly one opposite and the corners
//! around every vertex form a single fan.
#include "unfold/check_closed_manifold.h"

#include <unordered_map>

#include "unfold/edge_key.h"

namespace subfab::unfold_detail {

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

}  // namespace subfab::unfold_detail
