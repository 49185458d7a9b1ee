// SPDX-License-Identifier: GPL-3.0-or-later
//! \file hex_topology.h
//! Private: vertex adjacency of a hexahedral mesh (edge neighbours, incident
//! hexahedra, boundary flags), shared by projection and optimisation.
#pragma once

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

//! The 12 edges of a hexahedron as local corner pairs.
inline constexpr int kHexEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                         {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

}  // namespace subfab::detail
