// SPDX-License-Identifier: GPL-3.0-or-later
//! \file read_gcode.h
//! Reads back the G-code `write_gcode` emits (the subset of RS-274 it uses)
//! as straight tool moves, for the simulation. Not a general G-code reader:
//! anything else is refused with the line number.
#pragma once

#include <string>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

struct GcodeMove {
  bool rapid = false;  // G0 (else G1)
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();  // mm
  double feed = 0.0;   // mm/min (G1)
  int tool = 0;        // 0 for the first tool, +1 at every M0 (tool change)
  int line = 0;        // 1-based line number
};

struct GcodeRead {
  std::vector<GcodeMove> moves;  // moves whose start is fully known (X, Y and Z all set before)
  int num_lines = 0;
  int num_tool_changes = 0;      // M0 count
  bool spindle_on_for_every_cut = true;  // no G1 while the spindle is off (M5 or before M3)
  bool ended = false;                    // M2 or M30 seen
};

//! Parses `text`. Accepted: comments (...), '%' lines, G0 G1 G17 G21 G90 G94,
//! X Y Z F S words, M0 M2 M3 M5 M8 M9 M30. Motion is modal (G0/G1); F is
//! modal. \throw IoError naming `name`, the line and the word when anything
//! else appears (G20 inches, G91 relative, arcs, ...), or on G1 without a
//! feed.
GcodeRead read_gcode(const std::string& text, const std::string& name = "G-code");

}  // namespace subfab
