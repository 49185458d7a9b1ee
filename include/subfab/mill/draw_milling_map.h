// SPDX-License-Identifier: GPL-3.0-or-later
//! \file draw_milling_map.h
//! A top view of one milled block (issue 15 point 2, "shown"): one pixel per
//! simulation cell, X to the right, Y up, shaded by the block's surface
//! (light from the upper left) and coloured by what the check found there:
//!  - grey: off the block (the table);
//!  - tan: off the block but left by the tool (the fillet at the walls' foot);
//!  - magenta: unreachable (the ideal tool leaves more than the tolerance);
//!  - green -> yellow -> red: residual (scallop) 0.02 mm or less, 0.1 mm,
//!    0.3 mm or more;
//!  - blue: gouged deeper than the resolution (never, on a passing block).
#pragma once

#include <vector>

#include "subfab/core/write_png.h"
#include "subfab/mill/check_milling.h"

namespace subfab {

//! The picture of the maps check_milling() compared (same grid). Large
//! maps are drawn at one pixel per k x k cells (the cell of each block of k
//! x k that shows the most: gouge, then unreachable, then the largest
//! residual) so that neither side exceeds `max_side` pixels.
RgbImage draw_milling_map(const HeightMap& milled, const HeightMap& target, const std::vector<unsigned char>& footprint,
                          const HeightMap& ideal, const MillCheckOptions& options, int max_side = 1000);

}  // namespace subfab
