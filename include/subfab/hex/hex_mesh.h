// SPDX-License-Identifier: GPL-3.0-or-later
//! \file hex_mesh.h
//! The all-hexahedral mesh of Appendix D: flat arrays of vertex positions and
//! hexahedra, and the checks that make it usable for simulation
//! (conforming, closed quad boundary, consistently oriented).
//!
//! Corner order is VTK's (cell type 12), also Medit's and Gmsh's: 0-1-2-3 is
//! a quad whose right-hand normal points towards the opposite quad 4-5-6-7,
//! and corner i+4 is joined to corner i.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

using Hex = std::array<int, 8>;
using Quad = std::array<int, 4>;

//! An all-hexahedral mesh: #V positions (model units) and #H hexahedra
//! (0-based vertex indices, VTK order).
struct HexMesh {
  std::vector<Vec3> vertices;
  std::vector<Hex> hexes;

  std::size_t num_vertices() const { return vertices.size(); }
  std::size_t num_hexes() const { return hexes.size(); }
};

//! The six faces of a hexahedron as local corner indices, each ordered
//! counter-clockwise seen from outside (right-hand normal outwards).
inline constexpr std::array<std::array<int, 4>, 6> kHexFaces{{
    {0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};

//! Face f of hexahedron h as global vertex indices, outward.
Quad hex_face(const Hex& h, int f);

//! The boundary of the mesh: faces that belong to one hexahedron only,
//! oriented outwards (in the order hex by hex, face by face).
std::vector<Quad> boundary_quads(const HexMesh& mesh);

//! What check_hex_mesh() found.
struct HexMeshCheck {
  std::size_t num_boundary_quads = 0;
  std::size_t num_interior_quads = 0;      // shared by exactly two hexahedra
  std::size_t num_overshared_quads = 0;    // in three or more hexahedra (never valid)
  std::size_t num_same_side_quads = 0;     // shared by two hexahedra with the same orientation
  std::size_t num_degenerate_hexes = 0;    // a repeated corner index
  std::size_t num_nonmanifold_boundary_edges = 0;  // boundary edges not in exactly two boundary quads
  std::size_t num_coincident_vertices = 0; // distinct vertices at the same position (T-junction / crack)
  std::size_t num_unused_vertices = 0;
  //! Conforming, with a closed, manifold, consistently oriented quad boundary.
  bool valid() const {
    return num_overshared_quads == 0 && num_same_side_quads == 0 && num_degenerate_hexes == 0 &&
           num_nonmanifold_boundary_edges == 0 && num_coincident_vertices == 0;
  }
};

//! Checks that every face is shared by at most two hexahedra, with opposite
//! orientations when shared, that no two vertices coincide (a crack or a
//! T-junction would leave a duplicate) and that the boundary quads form a
//! closed 2-manifold (every boundary edge in exactly two boundary quads).
HexMeshCheck check_hex_mesh(const HexMesh& mesh);

//! Removes unused vertices and renumbers the hexahedra.
void compact_hex_mesh(HexMesh& mesh);

//! Surface of the boundary as triangles (each quad split along 0-2), with
//! the mesh's vertex indices.
Mesh boundary_triangles(const HexMesh& mesh);

}  // namespace subfab
