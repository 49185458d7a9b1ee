// SPDX-License-Identifier: GPL-3.0-or-later
//! \file mill_block.h
//! Everything `subfab mill` does for one block: place it in its stock, plan
//! roughing and finishing, write the G-code, read the G-code back, simulate
//! it on a height map and compare the result with the block.
//!
//! Machine frame (millimetres): milling direction +Z; X0 Y0 at the stock's
//! corner of least x and y; Z0 at the stock's bottom, which is the block's
//! base (the block sits on the table, `stock_margin` from the stock's sides).
//! Everything outside the block's footprint is cut down to Z0.
#pragma once

#include <string>
#include <vector>

#include "subfab/mill/check_milling.h"
#include "subfab/mill/draw_milling_map.h"
#include "subfab/mill/finish_toolpath.h"
#include "subfab/mill/machining_time.h"
#include "subfab/mill/rough_toolpath.h"
#include "subfab/mill/write_gcode.h"

namespace subfab {

struct MillOptions {
  RoughingOptions roughing;       // flat end mill, z levels
  FinishingOptions finishing;     // ball end mill, raster
  GcodeOptions gcode;             // dialect, feeds, spindle
  MotionLimits motion;            // acceleration of the time estimate (--accel)
  bool rough = true;              // plan the roughing pass (false: finishing only, e.g. on foam)
  double stock_margin = 5.0;      // --stock-margin: mm of stock around the block in x and y and above it
  double resolution = 0.25;       // --resolution: mm, side of a simulation cell
  MillCheckOptions check;
  bool picture = true;            // draw the top view of the check (MilledBlock::picture)
};

//! A block placed in its stock.
struct StockSetup {
  Mesh part;    // the block in the machine frame, mm
  Stock stock;  // mm
};

//! Scales a block's machine mesh (model units, base on z = 0, milling
//! direction +z, as `subfab decompose` writes mill/block_NNN.stl) by `scale`
//! mm per model unit and moves it `margin` mm in from the stock's corner.
//! \throw InvalidArgumentError when scale or margin is not positive/finite.
StockSetup place_in_stock(const Mesh& machine_mesh, double scale, double margin);

struct MilledBlock {
  Stock stock;
  std::string gcode;
  PathLengths rough, finish;         // mm
  double rough_time = 0.0, finish_time = 0.0;  // s, estimated from the feeds and the acceleration
  double time_no_accel = 0.0;        // s, lengths over feeds only (a lower bound)
  SimulationStats simulation;
  MillCheck check;
  int num_gcode_lines = 0;
  RgbImage picture{0, 0};            // draw_milling_map() of the check (empty unless options.picture)
};

//! Mills one placed block. `header` lines go first into the G-code's
//! comments (name the block). Deterministic whatever the thread count.
MilledBlock mill_block(const StockSetup& setup, const std::vector<std::string>& header, const MillOptions& options);

}  // namespace subfab
