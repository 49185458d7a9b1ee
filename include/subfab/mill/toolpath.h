// SPDX-License-Identifier: GPL-3.0-or-later
//! \file toolpath.h
//! What `subfab mill` plans before writing G-code: a list of straight moves
//! of one tool in the block's machine frame (millimetres; X0 Y0 at the
//! stock's corner of smallest x and y, Z0 at the stock's bottom, which is
//! the block's base), and their length and time.
#pragma once

#include <string>
#include <vector>

#include "subfab/mesh/mesh.h"
#include "subfab/mill/tool.h"

namespace subfab {

//! Rapid: G0 (never in material); Plunge: G1 straight down at the plunge
//! feed; Cut: G1 at the cutting feed.
enum class MoveKind { Rapid, Plunge, Cut };

struct Move {
  MoveKind kind = MoveKind::Cut;
  Vec3 to = Vec3::Zero();  // end point of the tool's reference point (mm)
};

//! The moves of one tool. The tool starts at the safe height above the
//! stock's origin corner, (0, 0, safe_z), and every toolpath of
//! rough_toolpath() and finish_toolpath() ends at the safe height.
struct Toolpath {
  Tool tool;
  std::string role;     // "roughing" or "finishing" (G-code comments)
  double safe_z = 0.0;  // mm: rapid moves between regions happen at or below it
  std::vector<Move> moves;
};

//! The stock: the box [0, x] x [0, y] x [0, z] in millimetres.
struct Stock {
  double x = 0, y = 0, z = 0;
};

//! Path lengths of a toolpath by kind of move, in mm.
struct PathLengths {
  double cut = 0.0;     // G1 at the cutting feed
  double plunge = 0.0;  // G1 at the plunge feed
  double rapid = 0.0;   // G0
};

//! The feeds a time estimate uses (mm/min).
struct Feeds {
  double feed = 1000.0;    // --feed: cutting feed, mm/min
  double plunge = 300.0;   // --plunge: plunge feed, mm/min
  double rapid = 3000.0;   // rapid rate assumed for G0 moves, mm/min (a hobby machine's; set to yours)
};

//! Lengths of the moves of `path`, starting from (0, 0, safe_z).
PathLengths path_lengths(const Toolpath& path);

//! Estimated time in seconds: every length over its feed (no acceleration).
double machining_time(const PathLengths& lengths, const Feeds& feeds);

}  // namespace subfab
