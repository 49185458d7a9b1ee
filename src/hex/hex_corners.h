// SPDX-License-Identifier: GPL-3.0-or-later
//! \file hex_corners.h
//! Private: the corner determinants of the scaled Jacobian (Verdict's
//! definition, see scaled_jacobian.h) seen from one vertex: which corners a
//! vertex moves, their values and the gradient of a corner with respect to
//! one of its four vertices, for the optimisers of D.6.
#pragma once

#include <vector>

#include "subfab/hex/hex_mesh.h"

namespace subfab::detail {

//! One corner of one hexahedron: hexahedron index and local corner (0-7).
struct HexCorner {
  int hex;
  int corner;
};

//! Per vertex: the corners whose determinant changes when it moves (its own
//! corner and its three edge neighbours' corners in each incident hexahedron),
//! in hexahedron order.
std::vector<std::vector<HexCorner>> vertex_corners(const HexMesh& mesh);

//! Determinant of the three normalised edge vectors of corner k; -1 when an
//! edge has zero length.
double corner_determinant(const HexMesh& mesh, const HexCorner& k);

//! The determinant of corner k and its gradient with respect to the
//! position of vertex v (one of the corner's four vertices; zero otherwise).
double corner_determinant_gradient(const HexMesh& mesh, const HexCorner& k, int v, Vec3& gradient);

//! The hexahedra around a vertex v, with the corners v does not move
//! evaluated once: while an optimiser's visit moves only v they are
//! constant, so the scaled Jacobians and energies of v's hexahedra need only
//! the corners v moves (half of them). Minima and sums run over the same
//! values in the same order as a full evaluation: bit-identical results.
struct VertexStar {
  std::size_t v = 0;
  const std::vector<int>* hexes = nullptr;  // v's hexahedra (HexTopology::vertex_hexes[v])
  std::vector<char> moved;                  // per (hexahedron, corner): v moves it
  std::vector<double> fixed_min;            // per hexahedron: min(1, the corners v does not move)
  std::vector<double> fixed_exp;            // per (hexahedron, corner) v does not move: exp(-sharpness x corner)
};

//! The star of v over `hexes`; fixed_exp only when sharpness > 0.
VertexStar vertex_star(const HexMesh& mesh, const std::vector<int>& hexes, std::size_t v, double sharpness = 0);

//! The scaled Jacobian of the j-th hexahedron of the star, at the current
//! position of its vertex (== scaled_jacobian(mesh, hexes[j])).
double star_hex_quality(const HexMesh& mesh, const VertexStar& star, std::size_t j);

}  // namespace subfab::detail
