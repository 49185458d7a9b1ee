// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_hex_mesh.h
//! Writing hexahedral meshes: Medit `.mesh` (HexaLab, Gmsh) and legacy VTK
//! unstructured grid (ParaView; cell type 12) with per-cell data.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "subfab/hex/hex_mesh.h"

namespace subfab {

//! Medit ASCII format (MeshVersionFormatted 2, Dimension 3, Vertices,
//! Hexahedra with 1-based indices, VTK corner order). \throw IoError.
void write_medit_hex_mesh(const HexMesh& mesh, const std::filesystem::path& path);

//! Legacy VTK ASCII unstructured grid, every cell a VTK_HEXAHEDRON (12); the
//! scalar `cell_data` (one value per hexahedron, may be empty) is written as
//! CELL_DATA named `cell_data_name`. \throw IoError.
void write_vtk_hex_mesh(const HexMesh& mesh, const std::filesystem::path& path,
                        const std::vector<double>& cell_data = {}, const std::string& cell_data_name = "scaled_jacobian");

}  // namespace subfab
