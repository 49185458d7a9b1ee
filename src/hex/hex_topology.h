// SPDX-License-Identifier: GPL-3.0-or-later
//! \file hex_topology.h
//! Private: vertex adjacency of a hexahedral mesh (edge neighbours, incident
//! hexahedra, boundary flags), shared by projection and optimisation.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "subfab/hex/hex_mesh.h"

namespace subfab::detail {

struct HexTopology {
  std::vector<std::vector<int>> vertex_hexes;         // per vertex: incident hexahedra
  std::vector<std::vector<int>> neighbors;            // per vertex: edge neighbours (sorted)
  std::vector<std::vector<int>> boundary_neighbors;   // per boundary vertex: neighbours along boundary edges
  std::vector<bool> on_boundary;
};

HexTopology hex_topology(const HexMesh& mesh);

class SurfaceProjector;

//! Per vertex, what the vertex optimisers need to move it: `scale`, the mean
//! length of its edges; `allowance`, for a boundary vertex, 0 when it lies
//! within on_surface x scale of the surface (it then slides on the surface),
//! else its distance from the surface (it may never go farther); -1 for an
//! inner vertex.
struct VertexAllowances {
  std::vector<double> scale;
  std::vector<double> allowance;
};
VertexAllowances vertex_allowances(const HexMesh& mesh, const HexTopology& topo, const SurfaceProjector& surface,
                                   double on_surface = 1e-9);

//! Grows `patch` (its entries the seeds, unchanged) by `rings` rings of edge
//! neighbours, breadth first: a neighbour w of the last ring joins when
//! `claim(w)` returns true (claim marks w so that it is not claimed twice:
//! the caller's marks decide whether patches may overlap). The order is
//! deterministic (ring by ring, neighbours sorted).
template <class Claim>
void grow_by_rings(std::vector<std::size_t>& patch, const HexTopology& topo, int rings, Claim&& claim) {
  for (std::size_t ring = 0, begin = 0; ring < static_cast<std::size_t>(std::max(rings, 0)); ++ring) {
    const std::size_t end = patch.size();
    for (std::size_t i = begin; i < end; ++i)
      for (int w : topo.neighbors[patch[i]])
        if (claim(static_cast<std::size_t>(w))) patch.push_back(static_cast<std::size_t>(w));
    begin = end;
  }
}

//! The 12 edges of a hexahedron as local corner pairs.
inline constexpr int kHexEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                         {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
//! The local axis of each edge of kHexEdges (0: corner 0 -> 1, 1: 0 -> 3,
//! 2: 0 -> 4).
inline constexpr int kHexEdgeAxis[12] = {0, 1, 0, 1, 0, 1, 0, 1, 2, 2, 2, 2};

}  // namespace subfab::detail
