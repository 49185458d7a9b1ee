// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/export_decomposition.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "decompose/single_precision_cleanup.h"
#include "geometry/rotate_accurately.h"
#include "subfab/core/error.h"
#include "subfab/decompose/finalize_blocks.h"
#include "subfab/geometry/rotate_into_frame.h"
#include "subfab/validate/block_thickness.h"
#include "subfab/validate/validate_decomposition.h"
#include "subfab/mesh/write_mesh.h"

namespace subfab {
namespace {

using Json = nlohmann::ordered_json;

Json vec_json(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json limit_json(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

std::string block_file(const char* folder, std::size_t i, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s/block_%03zu.%s", folder, i, ext);
  return buf;
}

//! The repair record of "input" (null when nothing was repaired).
Json repair_json(const DecomposeResult& result, const ExportInfo& info) {
  if (!result.repaired_input) return Json(nullptr);
  const RepairReport& r = result.repair;
  return {{"mesh", kRepairedInputFile},
          {"vertices", result.repaired_input->num_vertices()},
          {"faces", result.repaired_input->num_faces()},
          {"num_features", r.num_features},
          {"num_creases", r.num_creases},
          {"num_vertices", r.num_vertices},
          {"num_rounds", r.num_rounds},
          {"num_faces_removed", r.num_faces_removed},
          {"num_faces_new", r.num_faces_new},
          {"max_deviation", r.max_deviation},
          {"mean_deviation", r.mean_deviation},
          {"max_deviation_fraction", r.max_deviation_fraction()},
          {"mean_deviation_fraction", r.mean_deviation_fraction()},
          {"hausdorff_error", r.hausdorff_error},
          {"max_deviation_cap_fraction", info.options.max_deviation},
          {"precision_snap", result.num_snapped_vertices == 0
                                 ? Json(nullptr)
                                 : Json{{"coordinate_rounding", result.coordinate_rounding},
                                        {"snap_tolerance", result.frame_snap_tolerance},
                                        {"num_vertices_moved", result.num_snapped_vertices}}}};
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

Mesh machine_mesh_of(const Mesh& block, Axis axis, const Eigen::Matrix3d& rotation, Vec3* shift) {
  // An exact product (signed permutation), each coordinate rounded once.
  const Eigen::Matrix3d to_machine = axis_to_machine(axis) * rotation;
  Mesh m;
  m.faces = block.faces;
  m.vertices.reserve(block.num_vertices());
  BoundingBox box;
  for (const Vec3& v : block.vertices) {
    m.vertices.push_back(detail::rotate_accurately(to_machine, v));
    box.extend(m.vertices.back());
  }
  const Vec3 s = -box.min;
  for (Vec3& v : m.vertices) v += s;
  if (shift) *shift = s;
  return m;
}

std::vector<ExportedBlock> make_exported_blocks(const Mesh& input, const DecomposeResult& result,
                                                Progress* progress) {
  FinalizeOptions fo;
  fo.normal_tolerance = height_field_normal_tolerance(result.max_overhang_deg);
  fo.progress = progress;
  // After a repair (4.3.5) the blocks decompose the repaired input.
  const Mesh& decomposed = result.repaired_input ? *result.repaired_input : input;
  FinalizeResult finished = finalize_blocks(decomposed, result, fo);
  std::vector<ExportedBlock> out;
  out.reserve(finished.blocks.size());
  const double diagonal = bounding_box(decomposed).diagonal();  // as finalize_blocks()'s checks
  for (FinalBlock& b : finished.blocks) {
    ExportedBlock e;
    e.axis = b.axis;
    e.direction = b.direction;
    e.mesh = std::move(b.mesh);
    const Eigen::Matrix3d to_machine = axis_to_machine(b.axis) * result.rotation;
    Vec3 shift;
    e.machine_mesh = machine_mesh_of(e.mesh, b.axis, result.rotation, &shift);
    const BoundingBox mb = bounding_box(e.machine_mesh);
    // The STL stores float32: make sure the rounded mesh is still a solid.
    // When the cleanup cannot make it one, both meshes are kept as they were
    // (the block, valid in doubles, is not damaged by a partial cleanup; check
    // 8 reports the STL).
    const Mesh block_before = e.mesh, machine_before = e.machine_mesh;
    const detail::SinglePrecisionCleanup clean =
        detail::clean_block_for_stl(e.machine_mesh, e.mesh, to_machine, e.direction, diagonal, fo);
    e.single_precision_ok = clean.ok;
    if (!clean.ok) {
      e.mesh = block_before;
      e.machine_mesh = machine_before;
    }
    if (progress && (clean.num_collapsed > 0 || clean.num_nudged > 0 || !clean.ok)) {
      char buf[256];
      std::snprintf(buf, sizeof buf,
                    "block %zu: in single precision (STL) %zu vertices collapsed, %zu faces removed, %zu vertices "
                    "rounded the other way%s",
                    out.size(), clean.num_collapsed, clean.num_faces_removed, clean.num_nudged,
                    clean.ok               ? ""
                    : clean.block_invalid ? "; the repair made the block invalid, so its STL is still not a solid "
                                            "(validate check 8 will fail)"
                                          : "; its STL is still not a solid (validate check 8 will fail)");
      progress->warn(buf);
    }
    // The frame twin follows the single-precision cleanup (its collapses and moves).
    e.frame_mesh = e.mesh.vertices == block_before.vertices && e.mesh.faces == block_before.faces
                       ? std::move(b.frame_mesh)
                       : frame_twin(e.mesh, block_before, b.frame_mesh.vertices, result.rotation);
    const Eigen::Matrix3d back = result.rotation.transpose();
    for (std::size_t v = 0; v < e.mesh.num_vertices(); ++v)
      e.frame_rounding =
          std::max(e.frame_rounding, (e.mesh.vertices[v] - detail::rotate_accurately(back, e.frame_mesh.vertices[v])).norm());
    e.machine_transform.setIdentity();
    e.machine_transform.topLeftCorner<3, 3>() = to_machine;
    e.machine_transform.topRightCorner<3, 1>() = shift;
    e.height = mb.max.z() - mb.min.z();
    double lo = std::numeric_limits<double>::infinity();
    for (const Vec3& v : e.mesh.vertices) {
      lo = std::min(lo, v.dot(e.direction));
      e.bbox.extend(v);
    }
    e.base_offset = lo;
    e.volume = signed_volume(e.mesh);
    e.thickness = block_thickness(e.mesh, to_machine).thickness;
    e.max_overhang_deg = overhang_angle_deg(check_height_field(e.mesh, e.direction).steepest_cosine);
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
                  {"bbox_diagonal", diagonal},
                  {"repair", info.smoothing.is_object() ? Json(nullptr) : repair_json(result, info)},
                  {"mesh_repair", info.mesh_repair},
                  {"smoothing", info.smoothing}};
  // Which mesh the blocks decompose: the restored solid of --smooth, else the
  // thin-feature repair's, else the repaired solid of --repair, else the input file.
  doc["input"]["decomposed_mesh"] =
      info.smoothing.is_object() ? Json(info.smoothing.at("mesh"))
      : result.repaired_input    ? Json(kRepairedInputFile)
                            : (info.mesh_repair.is_object() ? Json(info.mesh_repair.at("mesh")) : Json(info.input_path));
  Json rot = Json::array();
  for (int r = 0; r < 3; ++r) rot.push_back(Json::array({result.rotation(r, 0), result.rotation(r, 1), result.rotation(r, 2)}));
  doc["rotation"] = rot;
  if (result.tolerance > 0) {  // the frame blocks (within a tolerance only: the exact output stays as it was)
    double rounding = 0.0;
    for (const ExportedBlock& b : blocks) rounding = std::max(rounding, b.frame_rounding);
    doc["frame"] = {{"snap_tolerance", result.frame_snap_tolerance}, {"max_rounding", rounding}};
  }
  const DecomposeOptions& o = info.options;
  doc["parameters"] = {{"max_height_fraction", limit_json(o.max_height_fraction)},
                       {"max_height", limit_json(result.max_height)},
                       {"machine", o.machine ? vec_json(*o.machine) : Json(nullptr)},
                       {"orient", o.orient},
                       {"grid_factor", o.grid_factor},
                       {"max_overhang_deg", result.max_overhang_deg},
                       {"tolerance", result.tolerance},
                       {"tolerance_fraction", diagonal > 0 ? result.tolerance / diagonal : 0.0}};
  if (result.tolerance > 0)  // within a tolerance only: the exact output stays as it was
    doc["parameters"]["tolerance_floor_scale"] = o.tolerance_floor_scale;
  if (!result.tolerance_fallback.empty())  // the thin-feature repair gave up at tolerance 0: why
    doc["parameters"]["tolerance_fallback"] = result.tolerance_fallback;
  Json list = Json::array();
  double total = 0.0, smallest = std::numeric_limits<double>::infinity(), steepest = 0.0;
  double thinnest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const ExportedBlock& b = blocks[i];
    Json m = Json::array();
    for (int r = 0; r < 4; ++r)
      m.push_back(Json::array({b.machine_transform(r, 0), b.machine_transform(r, 1), b.machine_transform(r, 2),
                               b.machine_transform(r, 3)}));
    Json entry;
    entry["id"] = i;
    entry["mesh"] = block_file("blocks", i, "obj");
    entry["machine_mesh"] = block_file("mill", i, "stl");
    if (result.tolerance > 0) entry["frame_mesh"] = block_file("frame", i, "obj");
    entry["direction"] = vec_json(b.direction);
    entry["axis"] = std::string(axis_name(b.axis));
    entry["base_offset"] = b.base_offset;
    entry["height"] = b.height;
    entry["volume"] = b.volume;
    entry["thickness"] = b.thickness;
    entry["max_overhang_deg"] = b.max_overhang_deg;
    entry["bbox"] = {{"min", vec_json(b.bbox.min)}, {"max", vec_json(b.bbox.max)}};
    entry["machine_transform"] = m;
    list.push_back(std::move(entry));
    total += b.volume;
    smallest = std::min(smallest, b.volume);
    thinnest = std::min(thinnest, b.thickness);
    steepest = std::max(steepest, b.max_overhang_deg);
  }
  doc["blocks"] = list;
  doc["summary"] = {{"num_blocks", blocks.size()},
                    {"material_volume_fraction", input_volume > 0 ? total / input_volume : 0.0},
                    {"min_block_volume_fraction", blocks.empty() || input_volume <= 0 ? 0.0 : smallest / input_volume},
                    {"min_thickness", blocks.empty() ? 0.0 : thinnest},
                    {"min_thickness_fraction", blocks.empty() || diagonal <= 0 ? 0.0 : thinnest / diagonal},
                    {"max_overhang_deg", steepest},
                    {"num_tolerance_merges", result.num_tolerance_merges},
                    {"num_allowed_faces", result.num_allowed_faces},
                    {"num_tolerance_rounds", result.num_tolerance_rounds},
                    {"tolerance_overhang_deg", result.tolerance_overhang_deg},
                    {"num_blocks_decomposed_in_place", result.num_blocks_decomposed_in_place},
                    {"num_sticking_out", std::count(result.filled.begin(), result.filled.end(), char{1})},
                    {"sliver_thickness", result.sliver_thickness},
                    {"num_slivers", result.num_slivers},
                    {"num_slivers_merged", result.num_slivers_merged},
                    {"num_slivers_dropped", result.num_slivers_dropped},
                    {"num_slivers_thickened", result.num_slivers_thickened},
                    {"num_slivers_recarved", result.num_slivers_recarved},
                    {"deviation_bound", result.deviation_bound},
                    {"deviation_bound_fraction", diagonal > 0 ? result.deviation_bound / diagonal : 0.0}};
  auto ms = [](double s) { return std::round(s * 1000.0) / 1000.0; };
  const DecomposeTimings& t = result.timings;
  doc["timings_s"] = {{"orient", ms(t.orient)}, {"field", ms(t.field)},     {"grow", ms(t.grow)},
                      {"cover", ms(t.cover)},   {"resolve", ms(t.resolve)}, {"carve", ms(t.carve)},
                      {"tolerance", ms(t.tolerance)}, {"total", ms(t.total)}};
  return doc.dump(2) + "\n";
}

std::vector<ExportedBlock> export_decomposition(const Mesh& input, const DecomposeResult& result,
                                                const ExportInfo& info, const std::filesystem::path& outdir) {
  namespace fs = std::filesystem;
  // Finish the blocks first: a block that cannot be made valid leaves the folder untouched.
  std::vector<ExportedBlock> blocks = make_exported_blocks(input, result, info.options.progress);
  std::error_code ec;
  const bool framed = result.tolerance > 0;  // frame/ within a tolerance only
  for (const char* sub : {"blocks", "mill", "frame"}) {
    if (sub == std::string("frame") && !framed) {
      if (!fs::is_directory(outdir / sub, ec)) continue;  // nothing stale to remove
    } else {
      fs::create_directories(outdir / sub, ec);
      if (ec) throw IoError((outdir / sub).string() + ": cannot create folder: " + ec.message());
    }
    // Remove block files of an earlier run (they would not be listed in the JSON).
    for (const auto& entry : fs::directory_iterator(outdir / sub, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("block_", 0) == 0) fs::remove(entry.path(), ec);
    }
  }
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    write_mesh(blocks[i].mesh, outdir / block_file("blocks", i, "obj"));
    write_mesh(blocks[i].machine_mesh, outdir / block_file("mill", i, "stl"));
    if (framed) write_mesh(blocks[i].frame_mesh, outdir / block_file("frame", i, "obj"));
  }
  const fs::path json_path = outdir / "decomposition.json";
  std::ofstream out(json_path, std::ios::binary);
  if (!out) throw IoError(json_path.string() + ": cannot write");
  out << decomposition_json(input, result, blocks, info);
  if (!out) throw IoError(json_path.string() + ": write failed (disk full?)");
  return blocks;
}

}  // namespace subfab
