// SPDX-License-Identifier: GPL-3.0-or-later
//! \file build_lattice.h
//! Stage 1 of the unfoldable simplification (thesis Section 3.3.1,
//! "Initialization"): a regular lattice over the padded bounding box of the
//! model, with an exact inside/outside sign at every lattice point.
#pragma once

#include <cstdint>
#include <vector>

#include "subfab/geometry/classify_grid_points.h"
#include "subfab/core/progress.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! A binary lattice: grid points with an inside (1) / outside (0) sign.
struct Lattice {
  GridPoints grid;                    // geometry of the points (x-fastest indexing)
  std::vector<std::uint8_t> inside;   // grid.num_points() signs: 1 inside, 0 outside

  bool is_inside(int i, int j, int k) const { return inside[grid.index(i, j, k)] != 0; }
  std::size_t num_inside() const;
};

//! Options of build_lattice().
struct LatticeOptions {
  double granularity = 2.0;             // lattice spacing = average edge length x granularity (> 0)
  int padding = 1;                      // layers of outside points around the bounding box (>= 1)
  std::size_t max_points = 64'000'000;  // refuse lattices with more points (memory guard)
  Progress* progress = nullptr;         // optional progress receiver
};

//! Builds the lattice of `mesh`: spacing = average_edge_length(mesh) x
//! granularity, the grid centred on the bounding box with `padding` outside
//! layers, and every point classified exactly (classify_grid_points(): a
//! point exactly on the surface is classified as a point infinitesimally
//! displaced by (e, e^2, e^3), so the rule is the same everywhere).
//! \param mesh closed, outward-oriented triangle mesh (model units).
//! \return the lattice; its outermost layers are all outside.
//! \throw InvalidArgumentError on a bad option or a lattice above max_points;
//!        InvalidMeshError on an empty mesh.
Lattice build_lattice(const Mesh& mesh, const LatticeOptions& options = {});

}  // namespace subfab
