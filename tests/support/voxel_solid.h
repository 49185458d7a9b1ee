// SPDX-License-Identifier: GPL-3.0-or-later
//! Closed solids made of unit voxels (unions of integer boxes), for the tests
//! of snap_and_shrink and resolve_overlaps: every configuration of the thesis
//! figures (L, T, crossing boxes, cycles) is a union of a few boxes.
#pragma once

#include <array>
#include <map>
#include <set>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab::test {

using Cell = std::array<int, 3>;

//! All unit cells of the integer box [lo, hi) (hi exclusive).
inline std::set<Cell> cells_of_box(const Cell& lo, const Cell& hi) {
  std::set<Cell> cells;
  for (int i = lo[0]; i < hi[0]; ++i)
    for (int j = lo[1]; j < hi[1]; ++j)
      for (int k = lo[2]; k < hi[2]; ++k) cells.insert({i, j, k});
  return cells;
}

//! Boundary of a union of unit cells: two outward-oriented triangles per
//! exposed cell face, vertices shared. Closed; manifold unless two cells
//! touch only along an edge or a corner (avoid that in tests).
inline Mesh voxel_mesh(const std::set<Cell>& cells) {
  Mesh mesh;
  std::map<Cell, int> vertex_of;
  auto vertex = [&](const Cell& p) {
    auto [it, inserted] = vertex_of.try_emplace(p, static_cast<int>(mesh.vertices.size()));
    if (inserted) mesh.vertices.emplace_back(p[0], p[1], p[2]);
    return it->second;
  };
  for (const Cell& c : cells)
    for (int k = 0; k < 3; ++k)
      for (int side : {-1, 1}) {
        Cell n = c;
        n[static_cast<std::size_t>(k)] += side;
        if (cells.count(n)) continue;
        // Face at x_k = c_k (side -1) or c_k + 1 (side +1); e_a x e_b = e_k.
        const auto a = static_cast<std::size_t>((k + 1) % 3), b = static_cast<std::size_t>((k + 2) % 3);
        Cell p0 = c;
        if (side > 0) p0[static_cast<std::size_t>(k)] += 1;
        Cell p1 = p0, p2 = p0, p3 = p0;
        p1[a] += 1;
        p2[a] += 1;
        p2[b] += 1;
        p3[b] += 1;
        const int v0 = vertex(p0), v1 = vertex(p1), v2 = vertex(p2), v3 = vertex(p3);
        if (side > 0) {
          mesh.faces.push_back({v0, v1, v2});
          mesh.faces.push_back({v0, v2, v3});
        } else {
          mesh.faces.push_back({v0, v2, v1});
          mesh.faces.push_back({v0, v3, v2});
        }
      }
  return mesh;
}

//! Union of integer boxes [lo, hi).
inline Mesh union_of_boxes(const std::vector<std::pair<Cell, Cell>>& boxes) {
  std::set<Cell> cells;
  for (const auto& [lo, hi] : boxes) cells.merge(cells_of_box(lo, hi));
  return voxel_mesh(cells);
}

}  // namespace subfab::test
