// SPDX-License-Identifier: GPL-3.0-or-later
//! Reads the model tables of data/MANIFEST.md and ../shared/models/MANIFEST.md
//! (name, vertex and face counts) for the reader tests.
#pragma once

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace subfab::test {

struct ManifestRow {
  std::string name;
  std::size_t vertices = 0;
  std::size_t faces = 0;
};

inline std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t`");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t`");
  return s.substr(b, e - b + 1);
}

//! Rows of the markdown table whose header starts with "| name |":
//! columns name, ..., verts (5th), faces (6th).
inline std::vector<ManifestRow> read_manifest(const std::filesystem::path& path) {
  std::vector<ManifestRow> rows;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| ", 0) != 0 || line.rfind("| name", 0) == 0 || line.rfind("|---", 0) == 0) continue;
    std::vector<std::string> cells;
    std::stringstream ss(line.substr(1));
    std::string cell;
    while (std::getline(ss, cell, '|')) cells.push_back(trim(cell));
    if (cells.size() < 6) continue;
    ManifestRow row;
    row.name = cells[0];
    row.vertices = std::stoul(cells[4]);
    row.faces = std::stoul(cells[5]);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace subfab::test
