// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/view/read_decomposition.h"

#include <nlohmann/json.hpp>

#include <fstream>

#include "subfab/core/error.h"
#include "subfab/mesh/read_mesh.h"

namespace subfab {
namespace {

using Json = nlohmann::json;

Vec3 vec3(const Json& j) {
  if (!j.is_array() || j.size() != 3) throw nlohmann::json::type_error::create(302, "expected [x, y, z]", &j);
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

}  // namespace

DecompositionFolder read_decomposition(const std::filesystem::path& outdir) {
  const std::filesystem::path json_path = outdir / "decomposition.json";
  std::ifstream in(json_path);
  if (!in)
    throw IoError(json_path.string() + ": cannot read; is " + outdir.string() +
                  " a folder written by `subfab decompose`?");
  DecompositionFolder f;
  f.folder = outdir;
  try {
    const Json doc = Json::parse(in);
    if (doc.value("format", "") != "subfab.decomposition")
      throw IoError(json_path.string() + ": not a subfab decomposition (\"format\" is not \"subfab.decomposition\")");
    f.input_path = doc.at("input").value("path", "");
    const Json& input = doc.at("input");
    const bool smoothed = input.contains("smoothing") && input.at("smoothing").is_object();
    const bool feature_repair = input.contains("repair") && !input.at("repair").is_null();
    // the file the blocks decompose (older files: the repaired input only)
    f.decomposed_mesh = input.value("decomposed_mesh", feature_repair ? "input_repaired.obj" : f.input_path);
    if (f.decomposed_mesh == f.input_path) f.decomposed_mesh.clear();
    f.model_label = f.decomposed_mesh.empty() ? "input model"
                    : !smoothed ? "repaired input"
                    : input.at("smoothing").value("restored", true) ? "restored input"
                                                                    : "smoothed input";
    f.bbox_diagonal = doc.at("input").value("bbox_diagonal", 0.0);
    const Json& rot = doc.at("rotation");
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) f.rotation(r, c) = rot.at(r).at(c).get<double>();
    for (const Json& b : doc.at("blocks")) {
      DecompositionBlock block;
      block.id = b.at("id").get<std::size_t>();
      block.axis = b.at("axis").get<std::string>();
      block.direction = vec3(b.at("direction"));
      block.volume = b.at("volume").get<double>();
      block.height = b.at("height").get<double>();
      block.max_overhang_deg = b.value("max_overhang_deg", 0.0);
      block.bbox.min = vec3(b.at("bbox").at("min"));
      block.bbox.max = vec3(b.at("bbox").at("max"));
      block.mesh = read_mesh(outdir / b.at("mesh").get<std::string>());
      // Stock: the block's bounding box in its machine frame (the rotation
      // part of machine_transform is a signed permutation times `rotation`).
      Eigen::Matrix3d m;
      const Json& t = b.at("machine_transform");
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m(r, c) = t.at(r).at(c).get<double>();
      BoundingBox machine;
      for (const Vec3& v : block.mesh.vertices) machine.extend(m * v);
      block.stock_size = machine.size();
      f.blocks.push_back(std::move(block));
    }
  } catch (const nlohmann::json::exception& e) {
    throw IoError(json_path.string() + ": malformed (" + e.what() + "); run `subfab decompose` again");
  }
  return f;
}

std::optional<Mesh> read_decomposed_model(const DecompositionFolder& folder, std::string* note) {
  std::vector<std::filesystem::path> candidates;
  if (!folder.decomposed_mesh.empty()) {
    candidates.push_back(folder.folder / folder.decomposed_mesh);
  } else if (!folder.input_path.empty()) {
    const std::filesystem::path p(folder.input_path);
    candidates.push_back(p);
    if (p.is_relative()) {
      candidates.push_back(folder.folder / p);
      candidates.push_back(folder.folder.parent_path() / p);
    }
  }
  std::string tried;
  for (const auto& c : candidates) {
    if (!tried.empty()) tried.append(", ");
    tried.append(c.string());
    std::error_code ec;
    if (!std::filesystem::is_regular_file(c, ec)) continue;
    try {
      return read_mesh(c);
    } catch (const Error& e) {
      tried.append(" (").append(e.what()).append(")");
    }
  }
  if (tried.empty()) tried = "nothing";
  if (note) *note = "the decomposed model was not found (tried: " + tried + ")";
  return std::nullopt;
}

}  // namespace subfab
