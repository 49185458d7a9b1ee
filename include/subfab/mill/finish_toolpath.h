// SPDX-License-Identifier: GPL-3.0-or-later
//! \file finish_toolpath.h
//! Finishing: a parallel (zig-zag) raster of a ball-end mill that follows
//! the drop-cutter surface of the block.
//!
//! Outline:
//!  1. raster lines along x, `stepover` x diameter apart in y (the last on
//!     the stock's far edge), joined at alternate ends by short links along
//!     y, so the whole finish is one continuous cut;
//!  2. along lines and links, points every `step` mm on the 0.001 mm grid,
//!     each at its drop-cutter height (rounded up to 0.001 mm);
//!  3. each segment is split at its midpoint while the drop-cutter height
//!     there or at either quarter point differs from the chord by more than
//!     `tolerance` (the midpoint alone misses S-shaped stretches, a crease
//!     then a ridge, whose chord crosses the surface); a segment too
//!     short to split (a vertical wall between its ends) is replaced by a
//!     vertical step up or down at the higher end, so the tool never goes
//!     through the wall;
//!  4. cross pass: where the drop-cutter surface rises towards +-y steeper
//!     than `cross_angle` (and steeper than towards +-x), the x raster's
//!     effective stepover along the wall grows as 1/cos of the slope and
//!     leaves tall scallops; lines along y, `stepover` x diameter apart in
//!     x, sweep those runs (grown by the tool radius each side, gaps up to a
//!     diameter bridged), refined as in 2-3. Each run is entered by rapids
//!     at a height proven above the material the x raster left (the highest
//!     mesh point within 2R + stepover/2 of the path, plus the tolerance,
//!     the ball's profile at stepover/2 and 1 mm), then a plunge;
//!  5. collinear moves are merged (within 0.0001 mm).
#pragma once

#include "subfab/mill/drop_cutter.h"
#include "subfab/mill/toolpath.h"

namespace subfab {

struct FinishingOptions {
  Tool tool{ToolShape::Ball, 6.0};  // --tool: the finishing end mill (ball or flat)
  double stepover = 0.1;            // --stepover: fraction of the tool diameter between raster lines, (0, 1]
  double step = 0.5;                // mm between base points along a line (> 0)
  double tolerance = 0.002;         // mm: largest gap between a move and the drop-cutter surface
  double safe_height = 5.0;         // mm above the stock top for rapid moves
  double cross_angle = 50.0;        // --cross-angle: degrees; a second raster along y where the surface is steeper
                                    // than this towards +-y (and than towards +-x); >= 90: none
};

//! The finishing toolpath of the mesh in `grid` (mm, machine frame, inside
//! `stock`). Deterministic whatever the thread count (lines in parallel,
//! written in order).
//! \throw InvalidArgumentError when an option is out of range.
Toolpath finish_toolpath(const TriangleGrid& grid, const Stock& stock, const FinishingOptions& options);

}  // namespace subfab
