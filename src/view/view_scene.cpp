// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/view/view_scene.h"

#include <algorithm>
#include <cstdio>
#include <tuple>

namespace subfab {

Rgb direction_color(const std::string& axis) {
  if (axis == "+x") return {215, 48, 48};    // red
  if (axis == "-x") return {40, 190, 190};   // cyan
  if (axis == "+y") return {60, 180, 60};    // green
  if (axis == "-y") return {190, 60, 190};   // magenta
  if (axis == "+z") return {60, 60, 225};    // blue
  if (axis == "-z") return {205, 205, 45};   // yellow
  return {150, 150, 150};
}

std::vector<std::array<int, 6>> hex_face_neighbors(const std::vector<std::array<int, 8>>& cells) {
  // Every face as (sorted corners, cell, face); equal keys are adjacent after sorting.
  using Key = std::array<int, 4>;
  std::vector<std::tuple<Key, int, int>> faces;
  faces.reserve(cells.size() * 6);
  for (std::size_t c = 0; c < cells.size(); ++c)
    for (int f = 0; f < 6; ++f) {
      Key key;
      for (int k = 0; k < 4; ++k) key[k] = cells[c][kViewHexFaces[f][k]];
      std::sort(key.begin(), key.end());
      faces.emplace_back(key, int(c), f);
    }
  std::sort(faces.begin(), faces.end());
  std::vector<std::array<int, 6>> out(cells.size());
  for (auto& n : out) n.fill(-1);
  for (std::size_t i = 0; i + 1 < faces.size(); ++i) {
    const auto& [key, c, f] = faces[i];
    const auto& [next_key, d, g] = faces[i + 1];
    if (key != next_key) continue;
    out[c][f] = d;
    out[d][g] = c;
    ++i;  // a face in three cells (never in a valid mesh) keeps its first pair
  }
  return out;
}

std::string to_hex(const Rgb& color) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", color[0] & 255, color[1] & 255, color[2] & 255);
  return buf;
}

}  // namespace subfab
