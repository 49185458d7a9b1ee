// SPDX-License-Identifier: GPL-3.0-or-later
#include "hex/hex_topology.h"

#include <algorithm>

#include "hex/surface_projector.h"

namespace subfab::detail {

HexTopology hex_topology(const HexMesh& mesh) {
  HexTopology t;
  const std::size_t n = mesh.vertices.size();
  t.vertex_hexes.resize(n);
  t.neighbors.resize(n);
  t.boundary_neighbors.resize(n);
  t.on_boundary.assign(n, false);
  auto link = [](std::vector<std::vector<int>>& lists, int a, int b) {
    lists[static_cast<std::size_t>(a)].push_back(b);
    lists[static_cast<std::size_t>(b)].push_back(a);
  };
  for (std::size_t h = 0; h < mesh.hexes.size(); ++h) {
    for (int v : mesh.hexes[h]) t.vertex_hexes[static_cast<std::size_t>(v)].push_back(static_cast<int>(h));
    for (const auto& e : kHexEdges)
      link(t.neighbors, mesh.hexes[h][static_cast<std::size_t>(e[0])], mesh.hexes[h][static_cast<std::size_t>(e[1])]);
  }
  for (const Quad& q : boundary_quads(mesh))
    for (std::size_t k = 0; k < 4; ++k) {
      t.on_boundary[static_cast<std::size_t>(q[k])] = true;
      link(t.boundary_neighbors, q[k], q[(k + 1) % 4]);
    }
  for (auto* lists : {&t.neighbors, &t.boundary_neighbors})
    for (auto& l : *lists) {
      std::sort(l.begin(), l.end());
      l.erase(std::unique(l.begin(), l.end()), l.end());
    }
  return t;
}

VertexAllowances vertex_allowances(const HexMesh& mesh, const HexTopology& topo, const SurfaceProjector& surface,
                                   double on_surface) {
  const std::size_t n = mesh.vertices.size();
  VertexAllowances a;
  a.scale.assign(n, 0.0);
  a.allowance.assign(n, -1.0);
  for (std::size_t v = 0; v < n; ++v) {
    double s = 0;
    for (int w : topo.neighbors[v]) s += (mesh.vertices[static_cast<std::size_t>(w)] - mesh.vertices[v]).norm();
    a.scale[v] = s / static_cast<double>(std::max<std::size_t>(1, topo.neighbors[v].size()));
    if (topo.on_boundary[v]) {
      const double d = (surface.closest_point(mesh.vertices[v]) - mesh.vertices[v]).norm();
      a.allowance[v] = d > on_surface * a.scale[v] ? d : 0.0;
    }
  }
  return a;
}

}  // namespace subfab::detail
