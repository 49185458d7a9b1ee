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

}  // namespace subfab::detail
