// SPDX-License-Identifier: GPL-3.0-or-later
//! \file pillow_hex_mesh.h
//! Pillowing (padding), thesis D.6: a layer of hexahedra over the whole
//! boundary, one per boundary quad, so that afterwards no hexahedron has
//! more than one face on the surface (Figure D.9) and the mesh keeps enough
//! freedom for the quality optimisation.
#pragma once

#include <vector>

#include "subfab/hex/hex_mesh.h"

namespace subfab {

//! Adds the padding layer in place. Every boundary vertex v gets a copy
//! outer[v] (the new boundary vertex, at v's position: the caller moves it),
//! and every boundary quad q = (a, b, c, d) the hexahedron
//! (a, b, c, d, outer[a], outer[b], outer[c], outer[d]).
//! Returns outer (-1 for vertices not on the old boundary).
std::vector<int> pillow_hex_mesh(HexMesh& mesh);

}  // namespace subfab
