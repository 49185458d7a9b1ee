// SPDX-License-Identifier: GPL-3.0-or-later
//! `subfab mill OUTDIR`: G-code per block of a decomposition folder, each
//! file simulated on its stock and checked against the block (issue 15).
//! Writes GCODE_DIR/block_NNN.nc and GCODE_DIR/mill.json; prints one row per
//! block. Exit 0 when every block is gouge-free, 3 when one is not, 2 when
//! the folder cannot be read.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "command.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/mesh/read_mesh.h"
#include "subfab/mill/mill_block.h"

namespace subfab::cli {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

struct MillArgs {
  std::string outdir;
  std::string gcode_dir;  // -o: default OUTDIR/gcode
  std::optional<double> size, scale;
  std::string tool = "ball:6", rough_tool = "flat:8";
  double stepover = 0.1, stepdown = 3.0, allowance = 0.5, cross_angle = 50.0;
  double feed = 1000.0, plunge = 300.0, rpm = 18000.0, rapid = 3000.0, accel = 500.0;
  double stock_margin = 5.0, resolution = 0.25;
  std::string dialect = "grbl";
  bool no_coolant = false;
  CommonOptions common;
};

struct BlockEntry {
  std::size_t id = 0;
  std::string axis;
  fs::path machine_mesh;
};

//! The blocks of decomposition.json and the model's largest dimension (the
//! union of the blocks' bounding boxes in input coordinates).
std::vector<BlockEntry> read_blocks(const fs::path& outdir, double& largest) {
  const fs::path path = outdir / "decomposition.json";
  std::ifstream in(path);
  if (!in) throw IoError(path.string() + ": cannot open (is this a folder written by subfab decompose?)");
  std::vector<BlockEntry> blocks;
  BoundingBox box;
  try {
    const nlohmann::json doc = nlohmann::json::parse(in);
    if (doc.at("format").get<std::string>() != "subfab.decomposition")
      throw IoError(path.string() + ": not a subfab.decomposition file");
    for (const auto& b : doc.at("blocks")) {
      BlockEntry e;
      e.id = b.at("id").get<std::size_t>();
      e.axis = b.at("axis").get<std::string>();
      e.machine_mesh = outdir / b.at("machine_mesh").get<std::string>();
      for (const char* corner : {"min", "max"}) {
        const auto& v = b.at("bbox").at(corner);
        box.extend(Vec3(v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>()));
      }
      blocks.push_back(std::move(e));
    }
  } catch (const nlohmann::json::exception& e) {
    throw IoError(path.string() + ": malformed: " + e.what());
  }
  if (blocks.empty()) throw IoError(path.string() + ": lists no blocks");
  largest = box.size().maxCoeff();
  return blocks;
}

std::string fmt(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

//! "block_007" + extension.
std::string block_name(std::size_t i, const char* extension = ".nc") {
  char buf[32];
  std::snprintf(buf, sizeof buf, "block_%03zu%s", i, extension);
  return buf;
}

Json lengths_json(const PathLengths& p) { return {{"cut", p.cut}, {"plunge", p.plunge}, {"rapid", p.rapid}}; }

bool block_passed(const MilledBlock& m) {
  return m.check.max_gouge <= m.check.resolution && m.simulation.num_rapid_cuts == 0;
}

int run_mill(const MillArgs& args) {
  if (args.size.has_value() == args.scale.has_value())
    throw InvalidArgumentError("give exactly one of --size L (largest model dimension in mm) or --scale S (mm per model unit)");
  MillOptions o;
  o.finishing.tool = parse_tool(args.tool);
  o.rough = args.rough_tool != "none";
  if (o.rough) o.roughing.tool = parse_tool(args.rough_tool);
  o.finishing.stepover = args.stepover;
  o.finishing.cross_angle = args.cross_angle;
  o.roughing.stepdown = args.stepdown;
  o.roughing.allowance = args.allowance;
  o.gcode.feeds = {args.feed, args.plunge, args.rapid};
  o.gcode.rpm = args.rpm;
  o.motion.accel = args.accel;
  o.gcode.coolant = !args.no_coolant;
  o.gcode.dialect = parse_dialect(args.dialect);
  o.stock_margin = args.stock_margin;
  o.resolution = args.resolution;

  const fs::path outdir(args.outdir);
  double largest = 0.0;
  const std::vector<BlockEntry> blocks = read_blocks(outdir, largest);
  if (!(largest > 0.0)) throw IoError((outdir / "decomposition.json").string() + ": the blocks have no extent");
  const double scale = args.scale ? *args.scale : *args.size / largest;
  const fs::path gdir = args.gcode_dir.empty() ? outdir / "gcode" : fs::path(args.gcode_dir);

  ConsoleProgress progress(std::cerr, args.common.quiet, stderr_is_terminal());
  std::vector<Mesh> meshes(blocks.size());
  {
    StageScope stage(&progress, "read");
    for (std::size_t i = 0; i < blocks.size(); ++i) meshes[i] = read_mesh(blocks[i].machine_mesh);
  }
  std::vector<MilledBlock> milled(blocks.size());
  {
    StageScope stage(&progress, "mill and simulate");
    std::size_t done = 0;
    std::mutex mutex;
    parallel_for(0, blocks.size(), [&](std::size_t i) {
      const StockSetup setup = place_in_stock(meshes[i], scale, o.stock_margin);
      const std::vector<std::string> header = {
          "subfab mill: block " + std::to_string(blocks[i].id) + " of " + std::to_string(blocks.size()) +
              ", milling direction " + blocks[i].axis + " of the model",
          "scale " + fmt("%.6g", scale) + " mm per model unit"};
      milled[i] = mill_block(setup, header, o);
      std::lock_guard<std::mutex> lock(mutex);
      progress.update(++done, blocks.size());
    });
  }

  std::error_code ec;
  fs::create_directories(gdir, ec);
  if (ec) throw IoError(gdir.string() + ": cannot create folder: " + ec.message());
  for (const auto& entry : fs::directory_iterator(gdir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("block_", 0) == 0 && (entry.path().extension() == ".nc" || entry.path().extension() == ".png"))
      fs::remove(entry.path(), ec);
  }
  Json list = Json::array();
  double total_time = 0.0, total_no_accel = 0.0, worst_gouge = 0.0;
  bool passed = true;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const MilledBlock& m = milled[i];
    const fs::path file = gdir / block_name(blocks[i].id);
    std::ofstream out(file, std::ios::binary);
    out << m.gcode;
    if (!out) throw IoError(file.string() + ": cannot write (disk full?)");
    write_png(m.picture, gdir / block_name(blocks[i].id, ".png"));
    const double time = m.rough_time + m.finish_time;
    total_time += time;
    total_no_accel += m.time_no_accel;
    worst_gouge = std::max(worst_gouge, m.check.max_gouge);
    passed = passed && block_passed(m);
    list.push_back({{"id", blocks[i].id},
                    {"gcode", block_name(blocks[i].id)},
                    {"axis", blocks[i].axis},
                    {"stock_mm", {m.stock.x, m.stock.y, m.stock.z}},
                    {"time_s", time},
                    {"time_no_accel_s", m.time_no_accel},
                    {"roughing_time_s", m.rough_time},
                    {"finishing_time_s", m.finish_time},
                    {"roughing_path_mm", lengths_json(m.rough)},
                    {"finishing_path_mm", lengths_json(m.finish)},
                    {"gcode_lines", m.num_gcode_lines},
                    {"picture", block_name(blocks[i].id, ".png")},
                    {"max_gouge_mm", m.check.max_gouge},
                    {"max_residual_mm", m.check.max_residual},
                    {"mean_residual_mm", m.check.mean_residual},
                    {"unreachable_area_mm2", m.check.unreachable_area},
                    {"unreachable_max_mm", m.check.unreachable_max},
                    {"foot_area_mm2", m.check.foot_area},
                    {"footprint_area_mm2", m.check.footprint_area},
                    {"rapid_cuts", m.simulation.num_rapid_cuts},
                    {"passed", block_passed(m)}});
  }
  Json doc;
  doc["format"] = "subfab.mill";
  doc["version"] = 1;
  doc["decomposition"] = args.outdir;
  doc["units"] = "mm";
  doc["scale_mm_per_unit"] = scale;
  doc["origin"] = "X0 Y0 at the stock corner of least x and y, Z0 at the stock bottom (the block's base)";
  doc["dialect"] = args.dialect;
  doc["roughing_tool"] = o.rough ? Json(tool_spec(o.roughing.tool)) : Json(nullptr);
  doc["finishing_tool"] = tool_spec(o.finishing.tool);
  doc["parameters"] = {{"stepover", args.stepover},         {"cross_angle_deg", args.cross_angle},
                       {"stepdown_mm", args.stepdown},
                       {"allowance_mm", args.allowance},    {"feed_mm_per_min", args.feed},
                       {"plunge_mm_per_min", args.plunge},  {"rapid_mm_per_min", args.rapid},
                       {"accel_mm_per_s2", args.accel},     {"junction_deviation_mm", o.motion.junction_deviation},
                       {"rpm", args.rpm},                   {"stock_margin_mm", args.stock_margin},
                       {"resolution_mm", args.resolution},  {"unreachable_tolerance_mm", o.check.unreachable_tolerance}};
  doc["picture_legend"] =
      "top view, X right, Y up, one pixel per simulation cell (or the most telling of k x k), shaded by the block: "
      "grey table, tan fillet left at the walls' foot, magenta unreachable, green residual <= 0.02 mm, yellow "
      "0.1 mm, red >= 0.3 mm, blue gouge deeper than the resolution";
  doc["blocks"] = list;
  doc["summary"] = {{"num_blocks", blocks.size()}, {"total_time_s", total_time},
                    {"total_time_no_accel_s", total_no_accel}, {"max_gouge_mm", worst_gouge},
                    {"passed", passed}};
  const fs::path json_path = gdir / "mill.json";
  std::ofstream jout(json_path, std::ios::binary);
  jout << doc.dump(2) << "\n";
  if (!jout) throw IoError(json_path.string() + ": cannot write");

  if (args.common.json) {
    std::cout << doc.dump(2) << "\n";
  } else if (!args.common.quiet) {
    std::ostringstream t;
    t << "mill " << args.outdir << ": " << blocks.size() << " blocks, scale " << fmt("%.6g", scale)
      << " mm per model unit, tools " << (o.rough ? tool_spec(o.roughing.tool) + " (roughing) + " : "")
      << tool_spec(o.finishing.tool) << " (finishing), simulated at " << fmt("%g", args.resolution) << " mm\n";
    char row[256];
    std::snprintf(row, sizeof row, "%-6s %-5s %-24s %9s %9s %9s %9s %12s %10s\n", "block", "axis", "stock mm",
                  "time min", "gouge mm", "resid max", "resid avg", "unreach mm2", "foot mm2");
    t << row;
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      const MilledBlock& m = milled[i];
      const std::string stock = fmt("%.1f", m.stock.x) + " x " + fmt("%.1f", m.stock.y) + " x " + fmt("%.1f", m.stock.z);
      std::snprintf(row, sizeof row, "%-6zu %-5s %-24s %9.1f %9.4f %9.3f %9.3f %12.1f %10.1f%s\n", blocks[i].id,
                    blocks[i].axis.c_str(), stock.c_str(), (m.rough_time + m.finish_time) / 60.0, m.check.max_gouge,
                    m.check.max_residual, m.check.mean_residual, m.check.unreachable_area, m.check.foot_area,
                    block_passed(m) ? "" : "  FAIL");
      t << row;
    }
    t << "total " << fmt("%.1f", total_time / 60.0) << " min (" << fmt("%.1f", total_no_accel / 60.0)
      << " without acceleration); max gouge " << fmt("%.4f", worst_gouge)
      << " mm (limit: the resolution); G-code and mill.json in " << gdir.string() << "\n";
    if (!passed) t << "milling check FAILED: a block is gouged deeper than the resolution or a rapid move cuts\n";
    std::cout << t.str();
  }
  return passed ? kExitOk : kExitFailed;
}

void add_mill_options(CLI::App& sub, MillArgs& args) {
  sub.add_option("OUTDIR", args.outdir, "Folder written by subfab decompose")->required();
  sub.add_option("-o,--output", args.gcode_dir, "Folder for the G-code and mill.json (default OUTDIR/gcode)");
  auto* size = sub.add_option("--size", args.size, "Scale the model so its largest dimension is L mm")
                   ->check(CLI::PositiveNumber);
  auto* scale = sub.add_option("--scale", args.scale, "Millimetres per model unit")->check(CLI::PositiveNumber);
  size->excludes(scale);
  sub.add_option("--tool", args.tool, "Finishing tool, ball:D or flat:D, D in mm (default ball:6)");
  sub.add_option("--rough-tool", args.rough_tool, "Roughing tool, flat:D in mm, or none (default flat:8)");
  sub.add_option("--stepover", args.stepover, "Finishing stepover, fraction of the tool diameter (default 0.1)")
      ->check(CLI::Range(0.001, 1.0));
  sub.add_option("--cross-angle", args.cross_angle,
                 "Second finishing raster along y where the surface is steeper than this towards +-y, degrees "
                 "(default 50; 90: none)")
      ->check(CLI::Range(1.0, 90.0));
  sub.add_option("--stepdown", args.stepdown, "Roughing depth per z level, mm (default 3)")->check(CLI::PositiveNumber);
  sub.add_option("--allowance", args.allowance, "Stock left by roughing for finishing, mm (default 0.5)")
      ->check(CLI::NonNegativeNumber);
  sub.add_option("--feed", args.feed, "Cutting feed, mm/min (default 1000)")->check(CLI::PositiveNumber);
  sub.add_option("--plunge", args.plunge, "Plunge feed, mm/min (default 300)")->check(CLI::PositiveNumber);
  sub.add_option("--rpm", args.rpm, "Spindle speed, rev/min (default 18000)")->check(CLI::PositiveNumber);
  sub.add_option("--rapid", args.rapid, "Rapid rate assumed by the time estimate, mm/min (default 3000)")
      ->check(CLI::PositiveNumber);
  sub.add_option("--accel", args.accel,
                 "Acceleration assumed by the time estimate, mm/s^2, all axes (default 500, a hobby router)")
      ->check(CLI::PositiveNumber);
  sub.add_option("--stock-margin", args.stock_margin, "Stock around the block in x and y and above it, mm (default 5)")
      ->check(CLI::NonNegativeNumber);
  sub.add_option("--resolution", args.resolution, "Simulation cell size, mm (default 0.25)")
      ->check(CLI::Range(0.02, 5.0));
  sub.add_option("--dialect", args.dialect, "G-code dialect: grbl or linuxcnc (default grbl)")
      ->check(CLI::IsMember({"grbl", "linuxcnc"}));
  sub.add_flag("--no-coolant", args.no_coolant, "Leave out the coolant commands M8/M9");
}

const RegisterCommand kRegisterMill(make_command<MillArgs>(
    "mill", 35,
    "Write G-code for every block of a folder written by `subfab decompose`: z-level roughing with a flat "
    "end mill, then a parallel raster with a ball end mill, at drop-cutter heights (the tool never goes "
    "below the block's surface), plain RS-274 for GRBL or LinuxCNC, in mm in the block's machine frame "
    "(milling direction +Z, X0 Y0 at a stock corner, Z0 at the stock bottom = block base). Each file is "
    "read back, simulated on a height map of its stock and compared with the block: gouge, residual "
    "(scallop) and the area the tool cannot reach. Writes GCODE_DIR/block_NNN.nc and GCODE_DIR/mill.json. "
    "Exit 0 if every block is gouge-free, 3 if not, 2 if the folder cannot be read.",
    add_mill_options, run_mill));

}  // namespace
}  // namespace subfab::cli
