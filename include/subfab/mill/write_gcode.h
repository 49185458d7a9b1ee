// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_gcode.h
//! Plain RS-274 G-code that GRBL (1.1) and LinuxCNC both run: G17 G21 G90
//! G94, G0/G1 with X Y Z F, S and M3/M5 (spindle), M8/M9 (coolant), M0
//! (pause for a tool change), M2/M30 (end); comments in parentheses; every
//! line at most 80 characters (GRBL's line buffer); numbers with 3 decimals.
//! No tool-length offsets, no arcs, no vendor extensions.
#pragma once

#include <string>
#include <vector>

#include "subfab/mill/toolpath.h"

namespace subfab {

//! Dialects differ only in comments and the program's end:
//! - grbl: plain comments, ends with M30;
//! - linuxcnc: the file is wrapped in '%' lines, the tool-change prompt is a
//!   (MSG, ...) comment LinuxCNC shows to the operator, ends with M2.
enum class GcodeDialect { Grbl, LinuxCnc };

//! "grbl" or "linuxcnc" -> dialect. \throw InvalidArgumentError otherwise.
GcodeDialect parse_dialect(const std::string& name);
std::string dialect_name(GcodeDialect dialect);

struct GcodeOptions {
  GcodeDialect dialect = GcodeDialect::Grbl;  // --dialect
  Feeds feeds;                                 // --feed, --plunge (mm/min)
  double rpm = 18000.0;                        // --rpm: spindle speed (S word)
  bool coolant = true;                         // M8 after spindle start, M9 before stop
  std::vector<std::string> header;             // extra comment lines (block, stock, scale, time), ASCII
};

//! The G-code of `paths` (run in order, the first tool loaded at the start,
//! a pause with M0 before each next tool). Coordinates as given, in mm.
//! Deterministic: same paths and options, same bytes.
std::string write_gcode(const std::vector<Toolpath>& paths, const Stock& stock, const GcodeOptions& options);

}  // namespace subfab
