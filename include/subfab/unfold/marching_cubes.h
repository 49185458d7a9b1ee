// SPDX-License-Identifier: GPL-3.0-or-later
//! \file marching_cubes.h
//! Stage 2 of the unfoldable simplification (thesis Section 3.2): marching
//! cubes on the binary lattice with every vertex at a lattice-edge midpoint,
//! so that every triangle normal is one of the 26 lattice directions.
#pragma once

#include <cstddef>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/mesh/mesh.h"
#include "subfab/unfold/build_lattice.h"

namespace subfab {

//! The marching-cubes surface of a lattice.
struct McSurface {
  Mesh mesh;                             // triangles, counter-clockwise seen from outside
  std::vector<int> normals;              // per triangle: index into lattice_directions()
  std::vector<std::size_t> vertex_edge;  // per vertex: its lattice edge, 3 * point index + axis
                                         // (the edge from that point along +axis)
};

//! Options of marching_cubes().
struct MarchingCubesOptions {
  Progress* progress = nullptr;  // optional progress receiver
};

//! Marching cubes on `lattice` with the generated case table (see
//! src/unfold/mc_case_table.h): vertices at the midpoints of the lattice
//! edges whose two end points have different signs (one vertex per lattice
//! edge, shared by the cubes around it), triangles oriented outward. When
//! the lattice's outer layer is all outside the surface is closed, 2-manifold
//! (inside corners that touch only diagonally are kept apart) and
//! consistently oriented.
//! \return vertices in increasing lattice-edge order, triangles in cube order
//!         (deterministic, independent of the thread count).
McSurface marching_cubes(const Lattice& lattice, const MarchingCubesOptions& options = {});

//! Triangles of one lattice cube with the given inside-corner bitmask
//! (bit c = corner at offset (c & 1, (c >> 1) & 1, (c >> 2) & 1)), as triples
//! of cube edge ids 0..11 (see mc_case_table.h), with their normal indices.
//! Exposed for the local updates of apply_masks().
const std::vector<std::array<int, 3>>& cube_triangles(int config);
const std::vector<int>& cube_triangle_normals(int config);

}  // namespace subfab
