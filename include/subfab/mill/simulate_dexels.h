// SPDX-License-Identifier: GPL-3.0-or-later
//! \file simulate_dexels.h
//! Height-map (dexel) simulation of a G-code program on its stock: one
//! vertical column of material per cell of a square grid, its height sampled
//! at the cell's centre. Each move lowers every column its tool sweeps to
//! the lowest point of the tool's lower surface over the move, computed in
//! closed form at the column's axis (a ball's sweep along a 3D segment and a
//! flat disk's are convex in the move parameter: the minimum is the clamped
//! stationary point or an end). So the simulated height at a cell centre is
//! exact up to rounding, whatever the resolution; the resolution only says
//! how densely the surface is sampled.
#pragma once

#include <cstddef>
#include <vector>

#include "subfab/mill/read_gcode.h"
#include "subfab/mill/tool.h"
#include "subfab/mill/toolpath.h"

namespace subfab {

//! Heights on a grid of nx x ny square cells of side `resolution` (mm) over
//! [0, nx * resolution] x [0, ny * resolution]; cell (i, j) is sampled at
//! ((i + 0.5) * resolution, (j + 0.5) * resolution).
struct HeightMap {
  int nx = 0, ny = 0;
  double resolution = 0.25;
  std::vector<double> z;  // [j * nx + i], mm

  double& at(int i, int j) { return z[static_cast<std::size_t>(j) * nx + i]; }
  double at(int i, int j) const { return z[static_cast<std::size_t>(j) * nx + i]; }
  double x(int i) const { return (i + 0.5) * resolution; }
  double y(int j) const { return (j + 0.5) * resolution; }
};

//! A height map covering the stock's xy extent, every cell at `height`.
HeightMap make_height_map(const Stock& stock, double resolution, double height);

//! Lowest height of the tool's lower surface at (x, y) while its reference
//! point moves straight from `a` to `b`; +infinity when the tool never covers
//! (x, y).
double swept_tool_height(const Tool& tool, const Vec3& a, const Vec3& b, double x, double y);

struct SimulationStats {
  std::size_t num_moves = 0;        // moves simulated
  std::size_t num_rapid_cuts = 0;   // G0 moves that removed material (must be 0)
  double max_rapid_cut = 0.0;       // mm: deepest material removed by a G0 move
};

//! Mills `stock_top` (the stock's heights, changed in place) with `program`;
//! tools[k] is the tool after k tool changes (M0). Moves run in order.
//! \throw InvalidArgumentError when the program changes tool more often than
//!        `tools` allows.
SimulationStats simulate_dexels(const GcodeRead& program, const std::vector<Tool>& tools, HeightMap& stock_top);

}  // namespace subfab
