// SPDX-License-Identifier: GPL-3.0-or-later
//! \file mc_case_table.h
//! The marching-cubes case table of Chapter 3 (thesis Section 3.2), generated
//! by program from explicit rules so that every triangle normal is one of the
//! 26 lattice directions (the classic Lorensen-Cline table breaks this on the
//! five-inside-corner cases).
//!
//! Cube conventions: corner c in 0..7 sits at offset (c & 1, (c >> 1) & 1,
//! (c >> 2) & 1). Edge e in 0..11 joins corners mc_edge(e).corners along axis
//! mc_edge(e).axis; its surface vertex is the edge midpoint. A case is the
//! bitmask of the inside corners (bit c set = corner c inside).
//!
//! Rules the generator applies:
//! 1. On every cube face, the surface cuts off each group of inside corners
//!    that are connected along face edges ("separate the inside corners":
//!    two diagonal inside corners are cut off separately). The rule depends
//!    only on the face's four signs, so neighbouring cubes agree and the
//!    surface is closed.
//! 2. Each face segment is oriented so that the inside is on its left seen
//!    from outside the cube; the segments chain into loops around the cube.
//! 3. Each loop is triangulated (among all of the polygon's triangulations)
//!    so that (a) every triangle normal is one of the 26 directions, (b) no
//!    two adjacent triangles fold back (normals with a negative dot product),
//!    and (c) no diagonal lies on a cube face, if possible; then the fewest
//!    distinct normals win, ties go to the first in enumeration order.
//! 4. 36 loops (six or seven vertices, in cases with five or six inside
//!    corners: twisted saddles) have no triangulation satisfying (a), (b)
//!    and (c), whatever consistent face rule is used (all 64 were tried).
//!    They need one diagonal lying on a cube face. Such a diagonal may be used
//!    by only one of the two cubes sharing the face (else the edge would have
//!    four triangles): a small depth-first search assigns each face diagonal
//!    (identified by the face's axis and its two midpoints, which both cubes
//!    see alike) to the low or the high cube so that every such loop has an
//!    admissible triangulation. The surface then touches a cube face along
//!    that diagonal, which is harmless (tests check manifoldness and the
//!    absence of self-intersections on all 256 cases and random lattices).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace subfab::mc {

//! One cube edge.
struct CubeEdge {
  std::array<int, 2> corners;  // corners[0] has the smaller offset along `axis`
  int axis;                    // 0 = x, 1 = y, 2 = z
};

//! The 12 cube edges, grouped by axis (4 x-edges, 4 y-edges, 4 z-edges).
const std::array<CubeEdge, 12>& cube_edges();

//! Doubled coordinates of edge e's midpoint (each coordinate in {0, 1, 2}).
std::array<int, 3> edge_midpoint2(int e);

//! Triangles of one case.
struct CubeCase {
  std::vector<std::array<int, 3>> triangles;  // cube edge ids, counter-clockwise seen from outside
  std::vector<int> normals;                   // per triangle: index into lattice_directions()
};

//! The 256 cases (generated once, thread-safe).
//! \throw AlgorithmError if the rules above have no solution (a bug).
const std::array<CubeCase, 256>& case_table();

}  // namespace subfab::mc
