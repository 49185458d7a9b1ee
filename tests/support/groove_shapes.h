// SPDX-License-Identifier: GPL-3.0-or-later
//! A 10 x 10 x 10 box with a groove 1 deep and 2 high running round its four
//! sides at z in [4, 6] (a shallow undercut no axis sees), and its two exact
//! height-field halves: the tests of the deviation meter and of the merges
//! within a tolerance. The deviation of the full box from the grooved one is
//! exactly 1 (the groove's back wall lies 1 under the box's side, and every
//! point of the box's side over the groove is 1 from the groove's surface).
#pragma once

#include <set>

#include "support/voxel_solid.h"

namespace subfab::test {

//! The groove's cells (k = 4, 5 on the outer ring of the box).
inline bool in_groove(const Cell& c) {
  return (c[2] == 4 || c[2] == 5) && (c[0] == 0 || c[0] == 9 || c[1] == 0 || c[1] == 9);
}

//! The cells of the grooved box; with `plug`, the groove on the +x side
//! (x in [9, 10], y in [1, 9]) is left full.
inline std::set<Cell> grooved_box_cells(bool plug = false) {
  std::set<Cell> cells;
  for (const Cell& c : cells_of_box({0, 0, 0}, {10, 10, 10}))
    if (!in_groove(c) || (plug && c[0] == 9 && c[1] >= 1 && c[1] <= 8)) cells.insert(c);
  return cells;
}

//! The cells of `cells` with z in [z0, z1), minus the plug when `no_plug`.
inline std::set<Cell> slab_of(const std::set<Cell>& cells, int z0, int z1, bool no_plug = false) {
  std::set<Cell> out;
  for (const Cell& c : cells)
    if (c[2] >= z0 && c[2] < z1 && !(no_plug && in_groove(c))) out.insert(c);
  return out;
}

}  // namespace subfab::test
