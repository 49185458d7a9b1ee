// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/export_decomposition.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <unordered_map>

#include "subfab/core/error.h"
#include "subfab/mesh/write_mesh.h"

namespace subfab {
namespace {

using Json = nlohmann::ordered_json;

struct VecHash {
  std::size_t operator()(const Vec3& v) const {
    std::size_t h = 0;
    for (int k = 0; k < 3; ++k) h = h * 1000003u ^ std::hash<double>()(v[k]);
    return h;
  }
};

Json vec_json(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json limit_json(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

std::string block_file(const char* folder, std::size_t i, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s/block_%03zu.%s", folder, i, ext);
  return buf;
}

}  // namespace

Eigen::Matrix3d axis_to_machine(Axis axis) {
  Eigen::Matrix3d q;
  switch (axis) {
    case Axis::PosZ: q << 1, 0, 0, 0, 1, 0, 0, 0, 1; break;
    case Axis::NegZ: q << 1, 0, 0, 0, -1, 0, 0, 0, -1; break;
    case Axis::PosX: q << 0, 1, 0, 0, 0, 1, 1, 0, 0; break;
    case Axis::NegX: q << 0, 0, 1, 0, 1, 0, -1, 0, 0; break;
    case Axis::PosY: q << 0, 0, 1, 1, 0, 0, 0, 1, 0; break;
    case Axis::NegY: q << 1, 0, 0, 0, 0, 1, 0, -1, 0; break;
  }
  return q;
}

std::vector<ExportedBlock> make_exported_blocks(const Mesh& input, const DecomposeResult& result) {
  std::unordered_map<Vec3, int, VecHash> input_vertex;
  const std::size_t n_in = std::min(result.num_input_vertices, result.canonical.num_vertices());
  for (std::size_t i = 0; i < n_in && i < input.num_vertices(); ++i)
    input_vertex.emplace(result.canonical.vertices[i], static_cast<int>(i));
  const Eigen::Matrix3d back = result.rotation.transpose();
  std::vector<ExportedBlock> out;
  out.reserve(result.blocks.size());
  for (const Block& b : result.blocks) {
    ExportedBlock e;
    e.axis = b.axis;
    e.direction = back * axis_direction(b.axis);
    e.mesh.faces = b.mesh.faces;
    e.mesh.vertices.reserve(b.mesh.num_vertices());
    for (const Vec3& c : b.mesh.vertices) {
      auto it = input_vertex.find(c);
      e.mesh.vertices.push_back(it != input_vertex.end() ? input.vertices[static_cast<std::size_t>(it->second)]
                                                         : Vec3(back * c));
    }
    // Machine mesh from the canonical coordinates: an exact signed permutation, then a shift.
    const Eigen::Matrix3d q = axis_to_machine(b.axis);
    e.machine_mesh.faces = b.mesh.faces;
    BoundingBox mb;
    for (const Vec3& c : b.mesh.vertices) {
      e.machine_mesh.vertices.push_back(q * c);
      mb.extend(e.machine_mesh.vertices.back());
    }
    const Vec3 shift = -mb.min;
    for (Vec3& v : e.machine_mesh.vertices) v += shift;
    e.machine_transform.setIdentity();
    e.machine_transform.topLeftCorner<3, 3>() = q * result.rotation;
    e.machine_transform.topRightCorner<3, 1>() = shift;
    e.height = mb.max.z() - mb.min.z();
    double lo = std::numeric_limits<double>::infinity();
    for (const Vec3& v : e.mesh.vertices) {
      lo = std::min(lo, v.dot(e.direction));
      e.bbox.extend(v);
    }
    e.base_offset = lo;
    e.volume = signed_volume(b.mesh);
    out.push_back(std::move(e));
  }
  return out;
}

std::string decomposition_json(const Mesh& input, const DecomposeResult& result,
                               const std::vector<ExportedBlock>& blocks, const ExportInfo& info) {
  const double diagonal = bounding_box(input).diagonal();
  const double input_volume = signed_volume(input);
  Json doc;
  doc["format"] = "subfab.decomposition";
  doc["version"] = 1;
  doc["input"] = {{"path", info.input_path},
                  {"vertices", input.num_vertices()},
                  {"faces", input.num_faces()},
                  {"bbox_diagonal", diagonal}};
  Json rot = Json::array();
  for (int r = 0; r < 3; ++r) rot.push_back(Json::array({result.rotation(r, 0), result.rotation(r, 1), result.rotation(r, 2)}));
  doc["rotation"] = rot;
  const DecomposeOptions& o = info.options;
  doc["parameters"] = {{"max_height_fraction", limit_json(o.max_height_fraction)},
                       {"max_height", limit_json(result.max_height)},
                       {"machine", o.machine ? vec_json(*o.machine) : Json(nullptr)},
                       {"orient", o.orient},
                       {"grid_factor", o.grid_factor}};
  Json list = Json::array();
  double total = 0.0, smallest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const ExportedBlock& b = blocks[i];
    Json m = Json::array();
    for (int r = 0; r < 4; ++r)
      m.push_back(Json::array({b.machine_transform(r, 0), b.machine_transform(r, 1), b.machine_transform(r, 2),
                               b.machine_transform(r, 3)}));
    list.push_back({{"id", i},
                    {"mesh", block_file("blocks", i, "obj")},
                    {"machine_mesh", block_file("mill", i, "stl")},
                    {"direction", vec_json(b.direction)},
                    {"axis", std::string(axis_name(b.axis))},
                    {"base_offset", b.base_offset},
                    {"height", b.height},
                    {"volume", b.volume},
                    {"bbox", {{"min", vec_json(b.bbox.min)}, {"max", vec_json(b.bbox.max)}}},
                    {"machine_transform", m}});
    total += b.volume;
    smallest = std::min(smallest, b.volume);
  }
  doc["blocks"] = list;
  doc["summary"] = {{"num_blocks", blocks.size()},
                    {"material_volume_fraction", input_volume > 0 ? total / input_volume : 0.0},
                    {"min_block_volume_fraction", blocks.empty() || input_volume <= 0 ? 0.0 : smallest / input_volume}};
  auto ms = [](double s) { return std::round(s * 1000.0) / 1000.0; };
  const DecomposeTimings& t = result.timings;
  doc["timings_s"] = {{"orient", ms(t.orient)}, {"field", ms(t.field)},     {"grow", ms(t.grow)},
                      {"cover", ms(t.cover)},   {"resolve", ms(t.resolve)}, {"carve", ms(t.carve)},
                      {"total", ms(t.total)}};
  return doc.dump(2) + "\n";
}

void export_decomposition(const Mesh& input, const DecomposeResult& result, const ExportInfo& info,
                          const std::filesystem::path& outdir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const char* sub : {"blocks", "mill"}) {
    fs::create_directories(outdir / sub, ec);
    if (ec) throw IoError((outdir / sub).string() + ": cannot create folder: " + ec.message());
    // Remove block files of an earlier run (they would not be listed in the JSON).
    for (const auto& entry : fs::directory_iterator(outdir / sub, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("block_", 0) == 0) fs::remove(entry.path(), ec);
    }
  }
  const std::vector<ExportedBlock> blocks = make_exported_blocks(input, result);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    write_mesh(blocks[i].mesh, outdir / block_file("blocks", i, "obj"));
    write_mesh(blocks[i].machine_mesh, outdir / block_file("mill", i, "stl"));
  }
  const fs::path json_path = outdir / "decomposition.json";
  std::ofstream out(json_path, std::ios::binary);
  if (!out) throw IoError(json_path.string() + ": cannot write");
  out << decomposition_json(input, result, blocks, info);
  if (!out) throw IoError(json_path.string() + ": write failed (disk full?)");
}

}  // namespace subfab
