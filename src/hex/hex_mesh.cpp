// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/hex_mesh.h"

#include <algorithm>
#include <map>
#include <tuple>

namespace subfab {
namespace {

std::array<int, 4> sorted(const Quad& q) {
  std::array<int, 4> s = q;
  std::sort(s.begin(), s.end());
  return s;
}

//! True when a and b list the same cycle in the same direction.
bool same_direction(const Quad& a, const Quad& b) {
  for (int k = 0; k < 4; ++k)
    if (a[0] == b[static_cast<std::size_t>(k)]) return a[1] == b[static_cast<std::size_t>((k + 1) % 4)];
  return false;
}

}  // namespace

Quad hex_face(const Hex& h, int f) {
  const auto& l = kHexFaces[static_cast<std::size_t>(f)];
  return {h[static_cast<std::size_t>(l[0])], h[static_cast<std::size_t>(l[1])], h[static_cast<std::size_t>(l[2])],
          h[static_cast<std::size_t>(l[3])]};
}

std::vector<Quad> boundary_quads(const HexMesh& mesh) {
  std::map<std::array<int, 4>, std::pair<int, Quad>> faces;
  std::vector<std::array<int, 4>> order;
  for (const Hex& h : mesh.hexes)
    for (int f = 0; f < 6; ++f) {
      const Quad q = hex_face(h, f);
      auto [it, inserted] = faces.try_emplace(sorted(q), std::pair<int, Quad>{0, q});
      if (inserted) order.push_back(it->first);
      ++it->second.first;
    }
  std::vector<Quad> out;
  for (const auto& key : order) {
    const auto& [count, q] = faces.at(key);
    if (count == 1) out.push_back(q);
  }
  return out;
}

HexMeshCheck check_hex_mesh(const HexMesh& mesh) {
  HexMeshCheck c;
  std::map<std::array<int, 4>, std::vector<Quad>> faces;
  for (const Hex& h : mesh.hexes) {
    std::array<int, 8> s = h;
    std::sort(s.begin(), s.end());
    if (std::adjacent_find(s.begin(), s.end()) != s.end()) ++c.num_degenerate_hexes;
    for (int f = 0; f < 6; ++f) faces[sorted(hex_face(h, f))].push_back(hex_face(h, f));
  }
  std::map<std::pair<int, int>, int> boundary_edges;
  for (const auto& [key, list] : faces) {
    if (list.size() == 1) {
      ++c.num_boundary_quads;
      for (int k = 0; k < 4; ++k) {
        const int a = list[0][static_cast<std::size_t>(k)], b = list[0][static_cast<std::size_t>((k + 1) % 4)];
        ++boundary_edges[{std::min(a, b), std::max(a, b)}];
      }
    } else if (list.size() == 2) {
      ++c.num_interior_quads;
      if (same_direction(list[0], list[1])) ++c.num_same_side_quads;
    } else {
      ++c.num_overshared_quads;
    }
  }
  for (const auto& [edge, count] : boundary_edges) c.num_nonmanifold_boundary_edges += count != 2;
  std::vector<bool> used(mesh.vertices.size(), false);
  for (const Hex& h : mesh.hexes)
    for (int v : h) used[static_cast<std::size_t>(v)] = true;
  std::vector<std::tuple<double, double, double, int>> positions;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (!used[v]) {
      ++c.num_unused_vertices;
      continue;
    }
    positions.emplace_back(mesh.vertices[v].x(), mesh.vertices[v].y(), mesh.vertices[v].z(), static_cast<int>(v));
  }
  std::sort(positions.begin(), positions.end());
  for (std::size_t i = 1; i < positions.size(); ++i)
    if (std::get<0>(positions[i]) == std::get<0>(positions[i - 1]) &&
        std::get<1>(positions[i]) == std::get<1>(positions[i - 1]) &&
        std::get<2>(positions[i]) == std::get<2>(positions[i - 1]))
      ++c.num_coincident_vertices;
  return c;
}

void compact_hex_mesh(HexMesh& mesh) {
  std::vector<int> index(mesh.vertices.size(), -1);
  std::vector<Vec3> vertices;
  for (Hex& h : mesh.hexes)
    for (int& v : h) {
      auto& i = index[static_cast<std::size_t>(v)];
      if (i < 0) {
        i = static_cast<int>(vertices.size());
        vertices.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
      }
      v = i;
    }
  mesh.vertices = std::move(vertices);
}

Mesh boundary_triangles(const HexMesh& mesh) {
  Mesh out;
  out.vertices = mesh.vertices;
  for (const Quad& q : boundary_quads(mesh)) {
    out.faces.push_back({q[0], q[1], q[2]});
    out.faces.push_back({q[0], q[2], q[3]});
  }
  return out;
}

}  // namespace subfab
