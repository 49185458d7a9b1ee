// SPDX-License-Identifier: GPL-3.0-or-later
//! \file rough_toolpath.h
//! Roughing: z-level passes of a flat end mill that clear the stock down to
//! the block's surface plus a stock allowance.
//!
//! Outline:
//!  1. raster lines along x, `stepover` x diameter apart in y, sampled every
//!     `step` mm; at each sample the drop-cutter height of a flat end of
//!     radius R + allowance + step/2, plus the allowance (so the real tool,
//!     anywhere between two samples, stays `allowance` clear of the surface);
//!  2. levels from the stock top down by `stepdown` to the lowest such height;
//!  3. at each level, along each line, the tool moves at max(level, height)
//!     through the runs of samples that still have material above them,
//!     climbing and descending in vertical steps (never diagonally through
//!     material); between runs it lifts to a height proven above the
//!     material left (the previous level or the surface bound of every
//!     sample whose tool disk can reach the link), never through material.
#pragma once

#include "subfab/mill/drop_cutter.h"
#include "subfab/mill/toolpath.h"

namespace subfab {

struct RoughingOptions {
  Tool tool{ToolShape::Flat, 8.0};  // --rough-tool: the roughing end mill
  double stepover = 0.45;           // fraction of the tool diameter between raster lines
  double stepdown = 3.0;            // --stepdown: mm between z levels (> 0)
  double allowance = 0.5;           // --allowance: mm of stock left for finishing (>= 0)
  double step = 1.0;                // mm between samples along a line (> 0)
  double clearance = 1.0;           // mm above the material left when entering it by a rapid
  double safe_height = 5.0;         // mm above the stock top for rapid moves across the stock
};

//! The roughing toolpath of the mesh in `grid` (mm, machine frame, inside
//! `stock`) with a flat end mill. Deterministic whatever the thread count
//! (drop-cutter samples in parallel, written in order).
//! \throw InvalidArgumentError when the tool is not a flat end mill or an
//!        option is out of range.
Toolpath rough_toolpath(const TriangleGrid& grid, const Stock& stock, const RoughingOptions& options);

}  // namespace subfab
