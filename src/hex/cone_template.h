// SPDX-License-Identifier: GPL-3.0-or-later
//! \file cone_template.h
//! Private: the cone template of D.5 (Figure D.6, 1x1 -> 2x2) applied to a
//! cone layer of a padded mesh (control_resolution.h explains its design).
#pragma once

#include "hex/hex_splitter.h"
#include "subfab/hex/control_resolution.h"

namespace subfab::detail {

//! Number of hexahedra of the template.
inline constexpr std::size_t kConeTemplateHexes = 58;

//! Appends the template's hexahedra for `layer` of `in` to `out` (whose
//! vertices start as `in`'s, as HexSplitter leaves them). Vertices on the
//! base face are the midpoints `splitter` gives the regular splits, so the
//! base side split at the same level is conforming with it; the tip face
//! keeps its corners only.
//! `cells` are the layer's 5 hexahedra (ConeLayer::hexes order) as they are
//! in `in` (for their orientation).
void add_cone_template(const HexMesh& in, const ConeLayer& layer, const std::array<Hex, 5>& cells,
                       HexSplitter& splitter, HexMesh& out);

}  // namespace subfab::detail
