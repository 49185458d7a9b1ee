// SPDX-License-Identifier: GPL-3.0-or-later
//! \file build_tubular_structure.h
//! The tubular structure of thesis Appendix D.3 (after Usai et al. 2015): a
//! coarse, conforming, all-hexahedral mesh that follows a resampled
//! curve-skeleton, inside the shape.
//!
//!   for every branching or terminal node (degree != 2):
//!     a cube (an n x n x n grid of hexahedra, half-size core_scale x the
//!     smallest radius among the node and its arcs' first inner nodes)
//!     oriented by the directions of its incident arcs: every candidate frame
//!     built from two arc directions is tried, each arc end is assigned its
//!     own face quad (optimal assignment when n = 1, greedy otherwise) and the
//!     frame whose worst arc-to-face angle is smallest wins; n = 1 when that
//!     angle is at most acos(min_dot) and at most 6 arcs meet, else n = 2, 3..
//!   for every arc:
//!     a tube with a one-quad cross-section, one layer of hexahedra per inner
//!     node, sections perpendicular to the arc, carried by parallel transport
//!     (rotation-minimising) from the start cube's face quad; at the end cube
//!     the cyclic shift of the face quad with the least twist is chosen and
//!     the remaining twist is spread evenly over the layers;
//!   a pure cycle (no branching node, e.g. a torus) is one closed tube.
//! Every face quad is used by one arc at most and each tube's end quads are
//! the cube face quads themselves, so the result is conforming by
//! construction: every interior quad is shared by exactly two hexahedra.
#pragma once

#include <cstddef>
#include <vector>

#include "subfab/hex/hex_mesh.h"
#include "subfab/hex/skeleton.h"

namespace subfab {

struct TubularStructureOptions {
  double core_scale = 0.6;  // half-size of cubes and tube sections, x the node's radius
  double min_dot = 0.5;     // worst accepted cos(angle) between an arc and its face's normal before subdividing
  double clearance = 1.25;  // arc nodes nearer a cube than this x its half-size (along the face normal) are skipped
};

//! The structure and what each element came from.
struct TubularStructure {
  HexMesh mesh;
  std::vector<int> hex_node;        // per hexahedron: skeleton node of its cube, -1 in a tube
  std::vector<int> hex_arc;         // per hexahedron: index of its arc in skeleton_arcs(), -1 in a cube
  std::vector<Vec3> vertex_anchor;  // per vertex: the skeleton point its cube or section is centred on
  std::size_t num_cubes = 0;
  std::size_t num_subdivided_cubes = 0;  // cubes that needed n >= 2
  std::size_t num_tubes = 0;
  double worst_arc_angle_deg = 0;        // largest angle between an arc and its face's direction
};

//! Builds the tubular structure of `skeleton` (normally resample_skeleton()'s).
//! \throw InvalidArgumentError for an empty skeleton.
TubularStructure build_tubular_structure(const Skeleton& skeleton, const TubularStructureOptions& options = {});

}  // namespace subfab
