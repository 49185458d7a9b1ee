// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_mesh.h
//! Writing triangle meshes: OBJ, OFF (text, exact double precision), binary
//! little-endian PLY, binary STL (float32, as the format requires).
#pragma once

#include <filesystem>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! Writes `mesh`; the format is chosen by the extension (.obj .off .ply .stl).
//! Text formats keep every double exactly (shortest representation that
//! reads back bit for bit, at most 17 significant digits).
//! \throw InvalidMeshError when a face index is out of range.
//! \throw IoError when the file cannot be written or the extension is unknown.
void write_mesh(const Mesh& mesh, const std::filesystem::path& path);

}  // namespace subfab
