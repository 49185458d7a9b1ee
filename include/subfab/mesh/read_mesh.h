// SPDX-License-Identifier: GPL-3.0-or-later
//! \file read_mesh.h
//! Reading triangle meshes from OBJ, OFF, PLY, STL and 3MF files.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

enum class MeshFormat { Obj, Off, Ply, Stl, ThreeMf };

//! "obj", "off", "ply", "stl", "3mf".
std::string format_name(MeshFormat format);

//! What the reader did besides reading (for `subfab info` and warnings).
struct ReadInfo {
  MeshFormat format = MeshFormat::Obj;
  std::size_t vertices_in_file = 0;       // vertex records in the file
  std::size_t polygons_in_file = 0;       // face records (before triangulation)
  std::size_t polygons_triangulated = 0;  // faces with more than 3 corners, fan-triangulated
  std::size_t unreferenced_removed = 0;   // vertices no face used, dropped
  std::size_t vertices_welded = 0;        // STL: exactly coincident corners merged
  std::vector<std::string> notes;         // other remarks (ignored mtllib, ...)
};

//! Reads a mesh; the format is chosen by the file extension (case-insensitive)
//! and, when the extension is unknown, by the file's content.
//! Polygons are triangulated, unreferenced vertices dropped, STL corners welded;
//! a 3MF file gives all its build items (transformed) as one mesh, in millimetres.
//! \throw IoError when the file cannot be opened or is not a well-formed file
//!        of its format (message: file, line or byte offset, what is wrong).
//! \throw InvalidMeshError when the file is well formed but holds no usable
//!        mesh: no faces, NaN/infinite coordinates, face indices out of range.
Mesh read_mesh(const std::filesystem::path& path, ReadInfo* info = nullptr);

}  // namespace subfab
