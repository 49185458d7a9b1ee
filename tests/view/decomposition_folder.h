// SPDX-License-Identifier: GPL-3.0-or-later
//! Test helper: small decomposition folders written by hand (the layout of
//! `subfab decompose`'s output, see src/decompose/export_decomposition.cpp),
//! and unions of boxes as block meshes.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "subfab/mesh/write_mesh.h"
#include "support/box_shapes.h"

namespace subfab::test {

//! The boxes (lo, hi pairs) as one mesh (separate closed components).
inline Mesh union_of_boxes(const std::vector<std::pair<Vec3, Vec3>>& boxes) {
  Mesh out;
  for (const auto& [lo, hi] : boxes) {
    const Mesh box = make_box_mesh(lo, hi);
    const int base = int(out.vertices.size());
    out.vertices.insert(out.vertices.end(), box.vertices.begin(), box.vertices.end());
    for (Triangle t : box.faces) out.faces.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return out;
}

//! A block of a hand-made folder: its mesh and milling axis ("+x" ... "-z").
struct FolderBlock {
  Mesh mesh;
  std::string axis;
};

//! Writes dir/decomposition.json and dir/blocks/block_NNN.obj (identity rotation).
inline void write_decomposition_folder(const std::filesystem::path& dir, const std::vector<FolderBlock>& blocks,
                                       const std::string& input_path = "box.obj") {
  std::filesystem::create_directories(dir / "blocks");
  nlohmann::ordered_json doc;
  doc["format"] = "subfab.decomposition";
  doc["version"] = 1;
  doc["input"] = {{"path", input_path}, {"bbox_diagonal", 1.0}, {"repair", nullptr}};
  doc["rotation"] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  doc["blocks"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "blocks/block_%03zu.obj", i);
    write_mesh(blocks[i].mesh, dir / name);
    const BoundingBox b = bounding_box(blocks[i].mesh);
    const int k = blocks[i].axis[1] - 'x';
    nlohmann::ordered_json direction = {0, 0, 0};
    direction[k] = blocks[i].axis[0] == '+' ? 1 : -1;
    doc["blocks"].push_back({{"id", i},
                             {"mesh", name},
                             {"direction", direction},
                             {"axis", blocks[i].axis},
                             {"height", b.size()[k]},
                             {"volume", signed_volume(blocks[i].mesh)},
                             {"max_overhang_deg", 0.0},
                             {"bbox", {{"min", {b.min.x(), b.min.y(), b.min.z()}}, {"max", {b.max.x(), b.max.y(), b.max.z()}}}},
                             {"machine_transform", {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}}});
  }
  std::ofstream(dir / "decomposition.json") << doc.dump(2);
}

//! A cup (base and four walls, five blocks) and a key inside it, touching
//! the base and the walls: the key can only leave upwards (+z), each wall
//! only outwards or upwards, the base only downwards once the key is out.
inline std::vector<FolderBlock> cup_and_key() {
  return {{make_box_mesh({0, 0, 0}, {3, 3, 1}), "-z"},  // 0 base
          {make_box_mesh({0, 0, 1}, {1, 3, 3}), "-x"},  // 1 wall at x < 1
          {make_box_mesh({2, 0, 1}, {3, 3, 3}), "+x"},  // 2 wall at x > 2
          {make_box_mesh({1, 0, 1}, {2, 1, 3}), "-y"},  // 3 wall at y < 1
          {make_box_mesh({1, 2, 1}, {2, 3, 3}), "+y"},  // 4 wall at y > 2
          {make_box_mesh({1, 1, 1}, {2, 2, 3}), "+z"}};  // 5 key
}

}  // namespace subfab::test
