// SPDX-License-Identifier: GPL-3.0-or-later
#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "hex/hex_topology.h"
#include "subfab/core/error.h"
#include "subfab/hex/hex_sheets.h"

namespace subfab {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

//! local coordinates of the VTK corners along the three axes
constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

std::pair<int, int> edge_key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

}  // namespace

SheetIrregularity sheet_irregularity(const HexMesh& mesh, const HexSheets& sheets) {
  if (sheets.of_hex.size() != mesh.hexes.size())
    throw InvalidArgumentError("sheet_irregularity: sheets of " + std::to_string(sheets.of_hex.size()) +
                               " hexahedra for a mesh of " + std::to_string(mesh.hexes.size()));
  // valence of every edge, and the edges of the boundary quads
  std::map<std::pair<int, int>, int> valence;
  for (const Hex& h : mesh.hexes)
    for (const auto& e : detail::kHexEdges) ++valence[edge_key(h[idx(e[0])], h[idx(e[1])])];
  std::set<std::pair<int, int>> boundary;
  for (const Quad& q : boundary_quads(mesh))
    for (int i = 0; i < 4; ++i) boundary.insert(edge_key(q[idx(i)], q[idx((i + 1) % 4)]));
  const std::size_t n = idx(sheets.num_sheets);
  SheetIrregularity r;
  r.size.assign(n, 0);
  r.along.assign(n, 0);
  r.freed.assign(n, 0);
  for (std::size_t h = 0; h < mesh.hexes.size(); ++h) {
    const auto& sh = sheets.of_hex[h];
    // where the irregular interior edges of h are: per axis, along it, or on
    // its low or high side (an edge not along an axis has one coordinate on it)
    std::array<bool, 3> along{}, low{}, high{};
    for (int e = 0; e < 12; ++e) {
      const int u = detail::kHexEdges[e][0], v = detail::kHexEdges[e][1];
      const auto key = edge_key(mesh.hexes[h][idx(u)], mesh.hexes[h][idx(v)]);
      if (valence.at(key) == 4 || boundary.count(key)) continue;
      for (int a = 0; a < 3; ++a) {
        if (a == detail::kHexEdgeAxis[e]) along[idx(a)] = true;
        else (kCorner[u][a] == 0 ? low : high)[idx(a)] = true;
      }
    }
    for (int a = 0; a < 3; ++a) {
      const int s = sh[idx(a)];
      if ((a > 0 && sh[0] == s) || (a > 1 && sh[1] == s)) continue;  // the sheet crosses itself in h: once
      ++r.size[idx(s)];
      if (along[idx(a)]) ++r.along[idx(s)];
      else if (low[idx(a)] != high[idx(a)]) ++r.freed[idx(s)];
    }
  }
  return r;
}

}  // namespace subfab
