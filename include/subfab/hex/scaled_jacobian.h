// SPDX-License-Identifier: GPL-3.0-or-later
//! \file scaled_jacobian.h
//! The scaled Jacobian of a hexahedron, the quality measure of Table D.1
//! (Verdict's definition, Stimpson et al. 2007): at each of the 8 corners,
//! the determinant of its three edge vectors, each normalised, taken in the
//! right-handed order; the minimum over the corners. 1 for a cube, sin(a)
//! for a cube sheared by angle a, <= 0 for an inverted or degenerate element.
#pragma once

#include <array>
#include <vector>

#include "subfab/hex/hex_mesh.h"

namespace subfab {

//! Scaled Jacobian of the hexahedron with corners p (VTK order), in [-1, 1];
//! -1 when an edge has zero length.
double scaled_jacobian(const std::array<Vec3, 8>& p);

//! Scaled Jacobian of hexahedron h of `mesh`.
double scaled_jacobian(const HexMesh& mesh, std::size_t h);

//! Scaled Jacobian of every hexahedron (in parallel, deterministic).
std::vector<double> scaled_jacobians(const HexMesh& mesh);

//! The smallest of `sj` (1 when empty: a mesh without hexahedra has no bad one).
double min_scaled_jacobian(const std::vector<double>& sj);

//! The mean of `sj`, summed serially in hexahedron order (the same value
//! whatever the thread count); 1 when empty.
double mean_scaled_jacobian(const std::vector<double>& sj);

//! The three neighbours of corner i (VTK order) such that
//! det(p[n0]-p[i], p[n1]-p[i], p[n2]-p[i]) > 0 for a positively oriented hex.
inline constexpr std::array<std::array<int, 3>, 8> kHexCornerNeighbors{{
    {1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7}, {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}}};

}  // namespace subfab
