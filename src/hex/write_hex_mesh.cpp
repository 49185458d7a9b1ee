// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/write_hex_mesh.h"

#include <fstream>
#include <iomanip>

#include "subfab/core/error.h"

namespace subfab {
namespace {

std::ofstream open(const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw IoError("cannot write " + path.string() + ": check the folder exists and is writable");
  out << std::setprecision(17);
  return out;
}

void finish(std::ofstream& out, const std::filesystem::path& path) {
  out.flush();
  if (!out) throw IoError("error while writing " + path.string() + " (disk full?)");
}

}  // namespace

void write_medit_hex_mesh(const HexMesh& mesh, const std::filesystem::path& path) {
  std::ofstream out = open(path);
  out << "MeshVersionFormatted 2\nDimension 3\nVertices\n" << mesh.vertices.size() << "\n";
  for (const Vec3& p : mesh.vertices) out << p.x() << ' ' << p.y() << ' ' << p.z() << " 0\n";
  out << "Hexahedra\n" << mesh.hexes.size() << "\n";
  for (const Hex& h : mesh.hexes) {
    for (int v : h) out << v + 1 << ' ';
    out << "0\n";
  }
  out << "End\n";
  finish(out, path);
}

void write_vtk_hex_mesh(const HexMesh& mesh, const std::filesystem::path& path, const std::vector<double>& cell_data,
                        const std::string& cell_data_name) {
  std::ofstream out = open(path);
  out << "# vtk DataFile Version 3.0\nsubfab hexahedral mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n";
  out << "POINTS " << mesh.vertices.size() << " double\n";
  for (const Vec3& p : mesh.vertices) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  out << "CELLS " << mesh.hexes.size() << ' ' << 9 * mesh.hexes.size() << '\n';
  for (const Hex& h : mesh.hexes) {
    out << 8;
    for (int v : h) out << ' ' << v;
    out << '\n';
  }
  out << "CELL_TYPES " << mesh.hexes.size() << '\n';
  for (std::size_t i = 0; i < mesh.hexes.size(); ++i) out << "12\n";
  if (!cell_data.empty()) {
    out << "CELL_DATA " << cell_data.size() << "\nSCALARS " << cell_data_name << " double 1\nLOOKUP_TABLE default\n";
    for (double q : cell_data) out << q << '\n';
  }
  finish(out, path);
}

}  // namespace subfab
