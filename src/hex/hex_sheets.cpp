// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/hex_sheets.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <utility>

#include "hex/hex_topology.h"

namespace subfab {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

int find(std::vector<int>& parent, int x) {
  while (parent[idx(x)] != x) {
    parent[idx(x)] = parent[idx(parent[idx(x)])];
    x = parent[idx(x)];
  }
  return x;
}

}  // namespace

HexSheets hex_sheets(const HexMesh& mesh) {
  // edges numbered in order of first appearance, joined to the opposite
  // edges of their faces (union-find)
  std::map<std::pair<int, int>, int> edge_id;
  std::vector<std::array<std::array<int, 4>, 3>> hex_edges(mesh.hexes.size());
  for (std::size_t h = 0; h < mesh.hexes.size(); ++h) {
    std::array<int, 3> filled{};  // edges of h stored per axis so far
    for (int e = 0; e < 12; ++e) {
      const int u = mesh.hexes[h][idx(detail::kHexEdges[e][0])], v = mesh.hexes[h][idx(detail::kHexEdges[e][1])];
      const auto it = edge_id.emplace(std::make_pair(std::min(u, v), std::max(u, v)),
                                      static_cast<int>(edge_id.size())).first;
      const int a = detail::kHexEdgeAxis[e];
      hex_edges[h][idx(a)][idx(filled[idx(a)]++)] = it->second;
    }
  }
  std::vector<int> parent(edge_id.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& he : hex_edges)
    for (const auto& four : he)
      for (int e = 1; e < 4; ++e) {
        const int a = find(parent, four[0]), b = find(parent, four[idx(e)]);
        if (a != b) parent[idx(std::max(a, b))] = std::min(a, b);
      }
  HexSheets s;
  s.of_hex.resize(mesh.hexes.size());
  std::vector<int> label(edge_id.size(), -1);
  for (std::size_t h = 0; h < mesh.hexes.size(); ++h)
    for (int a = 0; a < 3; ++a) {
      const int root = find(parent, hex_edges[h][idx(a)][0]);
      if (label[idx(root)] < 0) label[idx(root)] = s.num_sheets++;
      s.of_hex[h][idx(a)] = label[idx(root)];
    }
  return s;
}

}  // namespace subfab
