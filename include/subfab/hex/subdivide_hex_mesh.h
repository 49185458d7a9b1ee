// SPDX-License-Identifier: GPL-3.0-or-later
//! \file subdivide_hex_mesh.h
//! The regular 2 x 2 x 2 split of every hexahedron (thesis D.3, Figure D.6
//! "a regularly split hexahedron"): new vertices at edge midpoints, face
//! centres and cell centres (trilinear), shared between neighbours, so a
//! conforming mesh stays conforming.
#pragma once

#include "subfab/hex/hex_mesh.h"

namespace subfab {

//! One level of regular subdivision: 8 x the hexahedra. Children of
//! hexahedron h are 8h .. 8h+7. Old vertices keep their indices.
HexMesh subdivide_hex_mesh(const HexMesh& mesh);

}  // namespace subfab
