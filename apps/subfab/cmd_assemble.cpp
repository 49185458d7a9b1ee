// SPDX-License-Identifier: GPL-3.0-or-later
//! `subfab assemble OUTDIR [--mill GCODE_DIR] [--size L | --scale S]`: the
//! cut list and gluing order of a decomposition, as OUTDIR/assembly.html.
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "command.h"
#include "subfab/view/write_assembly_sheet.h"

namespace subfab::cli {
namespace {

struct AssembleArgs {
  std::string outdir;
  std::string mill_dir;
  double size_mm = 0;
  double scale = 0;
  int picture_size = 200;
  int resolution = 200;
  CommonOptions common;
};

int run_assemble(const AssembleArgs& args) {
  ConsoleProgress progress(std::cerr, args.common.quiet, stderr_is_terminal());
  AssemblySheetOptions options;
  options.mill_dir = args.mill_dir;
  options.size_mm = args.size_mm;
  options.mm_per_unit = args.scale;
  options.picture_size = args.picture_size;
  options.resolution = args.resolution;
  options.progress = &progress;
  AssemblySheet sheet;
  {
    StageScope stage(&progress, "assemble");
    sheet = write_assembly_sheet(args.outdir, options);  // IoError: exit 2
  }
  const GluingPlan& plan = sheet.plan;
  const DecompositionFolder folder = read_decomposition(args.outdir);
  if (args.common.json) {
    nlohmann::ordered_json j;
    j["output"] = args.outdir + "/assembly.html";
    j["mm_per_unit"] = sheet.mm_per_unit > 0 ? nlohmann::ordered_json(sheet.mm_per_unit) : nlohmann::ordered_json(nullptr);
    j["total_time_s"] = sheet.total_time_s >= 0 ? nlohmann::ordered_json(sheet.total_time_s) : nlohmann::ordered_json(nullptr);
    j["ray_spacing"] = plan.ray_spacing;
    j["steps"] = nlohmann::ordered_json::array();
    for (const GluingStep& s : plan.steps)
      j["steps"].push_back({{"block", folder.blocks[s.block].id},
                            {"from", s.axis >= 0 ? nlohmann::ordered_json(axis_label(s.axis)) : nlohmann::ordered_json(nullptr)}});
    j["stuck"] = nlohmann::ordered_json::array();
    for (std::size_t b : plan.stuck) j["stuck"].push_back(folder.blocks[b].id);
    std::cout << j.dump(2) << "\n";
  } else if (!args.common.quiet) {
    std::cout << "gluing order:";
    for (const GluingStep& s : plan.steps)
      std::cout << " " << folder.blocks[s.block].id << (s.axis >= 0 ? "(from " + axis_label(s.axis) + ")" : "");
    std::cout << "\n";
    if (!plan.stuck.empty())
      std::cout << plan.stuck.size() << " blocks interlock (no single straight move frees one): assemble them first, together\n";
    std::cout << "wrote " << args.outdir << "/assembly.html (sizes in "
              << (sheet.mm_per_unit > 0 ? "mm" : "model units: give --size, --scale or --mill for mm") << ")\n";
  }
  return kExitOk;
}

void add_assemble_options(CLI::App& sub, AssembleArgs& args) {
  sub.add_option("OUTDIR", args.outdir, "Folder written by `subfab decompose`")->required();
  sub.add_option("--mill", args.mill_dir,
                 "Folder written by `subfab mill` (its mill.json gives stock sizes in mm, machining times, the scale)");
  auto* size = sub.add_option("--size", args.size_mm, "The model's largest dimension in mm (sets the scale)")
                   ->check(CLI::PositiveNumber);
  sub.add_option("--scale", args.scale, "Millimetres per model unit")->check(CLI::PositiveNumber)->excludes(size);
  sub.add_option("--picture-size", args.picture_size, "Pixels per side of each picture (default 200)")
      ->check(CLI::Range(32, 1024));
  sub.add_option("--resolution", args.resolution,
                 "Rays per side of the model for the gluing order's blocking test (default 200)")
      ->check(CLI::Range(8, 2048));
}

const RegisterCommand kRegisterAssemble(make_command<AssembleArgs>(
    "assemble", 25,
    "Write OUTDIR/assembly.html for a decomposition: a printable cut list (stock size, milling direction, "
    "machining time per block) and a gluing order in which every block slides into place along a free axis, "
    "with a picture of each block and of where it goes. Exit 2 if OUTDIR or mill.json cannot be read.",
    add_assemble_options, run_assemble));

}  // namespace
}  // namespace subfab::cli
