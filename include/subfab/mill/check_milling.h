// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_milling.h
//! Compares a simulated milled surface (simulate_dexels) with the block it
//! should be: the block's top surface sampled at the same cell centres.
//!
//! - target T: the highest point of the block above each cell centre (exact
//!   point-in-triangle and plane height over the upward-facing triangles),
//!   0 (the table) outside the block's footprint;
//! - ideal surface M: what the finishing tool can reach at best, the lowest
//!   lower surface over tool positions at every cell centre, each at its
//!   drop-cutter height (a morphological opening of T by the tool, sampled
//!   at the grid);
//! - gouge: T - S where the simulated surface S lies below the target;
//! - unreachable: cells where M - T exceeds `unreachable_tolerance`: the tool
//!   is too wide to get there (narrow grooves, inside corners). On the
//!   block's footprint they count as unreachable area; off it (at the foot of
//!   the block's walls, where a ball leaves a fillet) as foot area;
//! - residual S - T on the reachable cells of the footprint (scallops).
#pragma once

#include <cstddef>

#include "subfab/mill/drop_cutter.h"
#include "subfab/mill/simulate_dexels.h"

namespace subfab {

struct MillCheckOptions {
  double unreachable_tolerance = 0.1;  // mm of material the ideal tool leaves before a cell counts as unreachable
};

struct MillCheck {
  double resolution = 0.0;          // mm, side of a simulation cell
  double max_gouge = 0.0;           // mm, largest T - S (0 when S >= T everywhere)
  double max_residual = 0.0;        // mm, largest S - T on reachable footprint cells
  double mean_residual = 0.0;       // mm, mean S - T on reachable footprint cells
  double unreachable_area = 0.0;    // mm^2 of footprint cells the tool cannot reach
  double unreachable_max = 0.0;     // mm, thickest material the ideal tool leaves on the footprint
  double foot_area = 0.0;           // mm^2 of off-footprint cells left (fillet around the walls' foot)
  double footprint_area = 0.0;      // mm^2 of cells under the block's top surface
  std::size_t num_cells = 0;        // cells simulated
};

//! The block's top surface T at the cell centres of `like` (its grid), and
//! in `footprint` 1 for cells under the block, 0 elsewhere.
HeightMap target_heights(const Mesh& block, const HeightMap& like, std::vector<unsigned char>& footprint);

//! The ideal surface M of `tool` over the mesh of `grid` at the cell centres
//! of `like`. Parallel over rows; deterministic.
HeightMap ideal_surface(const TriangleGrid& grid, const Tool& tool, const HeightMap& like);

//! Compares the simulated surface `milled` with target and ideal surface.
MillCheck check_milling(const HeightMap& milled, const HeightMap& target, const std::vector<unsigned char>& footprint,
                        const HeightMap& ideal, const MillCheckOptions& options = {});

}  // namespace subfab
