// SPDX-License-Identifier: GPL-3.0-or-later
//! \file hex_sheets.h
//! Sheets of a hexahedral mesh and where its irregular edges are (not in the
//! thesis; issue 14, docs/hexmesh.md "4c. Finest level keeping the layers").
//!
//! A sheet is a class of topologically parallel edges: two edges are in the
//! same class when they are opposite edges of a face, so the class closes
//! over the whole mesh (its dual is a layer of hexahedra). Splitting every
//! edge of some sheets at its midpoint, and every hexahedron across each
//! axis whose sheet is one of them, keeps a conforming mesh conforming (the
//! two hexahedra of a face split it along the same axes); the regular
//! 2 x 2 x 2 split of D.3 splits every sheet.
//!
//! Why it matters for the quality: around a valence-3 edge (the corners of
//! a tube's one-quad core, pillowed, run along the tube) the three dihedral
//! angles sum to 360 degrees, so the hexahedra touching it have a scaled
//! Jacobian of at most sin 120 = .866. A tube's layer sheets (one layer of
//! the tube: its hexahedra all touch those edges, along the sheet's axis)
//! split only add such capped hexahedra: both children keep the edge.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "subfab/hex/hex_mesh.h"

namespace subfab {

//! The sheets of a hexahedral mesh. Ids 0 .. num_sheets - 1 in order of
//! first appearance (hexahedron by hexahedron, axis by axis): deterministic.
struct HexSheets {
  //! per hexahedron, the sheet of its edges along local axis 0 (VTK corner
  //! 0 -> 1), 1 (0 -> 3), 2 (0 -> 4)
  std::vector<std::array<int, 3>> of_hex;
  int num_sheets = 0;
};
HexSheets hex_sheets(const HexMesh& mesh);

//! Per sheet: `size`, its hexahedra; `along`, those with an irregular
//! interior edge (valence other than 4, not on the boundary) along the
//! sheet's axis in them (splitting the sheet gives two children that both
//! keep that edge); `freed`, those with irregular interior edges, none along
//! the sheet's axis and all on one side of it (splitting the sheet gives one
//! child that touches none). A hexahedron in which the sheet crosses itself
//! counts once, for its first axis.
struct SheetIrregularity {
  std::vector<std::size_t> size, along, freed;
};
SheetIrregularity sheet_irregularity(const HexMesh& mesh, const HexSheets& sheets);

}  // namespace subfab
