// SPDX-License-Identifier: GPL-3.0-or-later
//! What the subcommands share (see command.h): the common options, the
//! reading of a solid input, number parsing.
#include "command.h"

#include <unistd.h>

#include <cmath>
#include <exception>

#include "subfab/checks/require_closed_solid.h"
#include "subfab/core/error.h"
#include "subfab/mesh/read_mesh.h"
#include "subfab/mesh/write_mesh.h"
#include "subfab/repair/mesh_repair_to_json.h"

namespace subfab::cli {

void add_common_options(CLI::App& sub, CommonOptions& options) {
  sub.add_option("--threads", options.threads, "Worker threads (0 = all cores); results do not depend on it")
      ->default_val(0)
      ->check(CLI::NonNegativeNumber);
  sub.add_flag("--quiet,-q", options.quiet, "Print only warnings and errors on stderr");
  sub.add_flag("--json", options.json, "Print a machine-readable summary as JSON on stdout");
}

void add_solid_input(CLI::App& sub, std::string& mesh) {
  sub.add_option("MESH", mesh, "Input mesh (.obj .off .ply .stl .3mf), a closed solid")->required();
}

void add_output_folder(CLI::App& sub, std::string& outdir) {
  sub.add_option("-o,--output", outdir, "Output folder (created if needed)")->required();
}

bool stderr_is_terminal() { return isatty(STDERR_FILENO) == 1; }

Mesh read_mesh_stage(const std::string& path, Progress& progress) {
  StageScope stage(&progress, "read");
  return read_mesh(path);  // IoError / InvalidMeshError: exit 2
}

void write_mesh_stage(const Mesh& mesh, const std::string& path, Progress& progress) {
  StageScope stage(&progress, "write");
  write_mesh(mesh, path);
}

Mesh read_closed_solid(const std::string& path, Progress& progress, const std::string& hint) {
  Mesh mesh = read_mesh_stage(path, progress);
  try {
    require_closed_solid(mesh, &progress);  // InvalidMeshError: exit 2, with the reason
  } catch (const InvalidMeshError& e) {
    if (hint.empty()) throw;
    throw InvalidMeshError(std::string(e.what()) + hint);
  }
  return mesh;
}

void add_repair_input_options(CLI::App& sub, RepairInputOptions& options) {
  sub.add_flag("--repair", options.repair,
               "Repair the input first when it is not a valid solid (as `subfab repair`: merge, orient, fill holes, "
               "resolve self-intersections, ...) and work on the repaired solid, written to OUTDIR/" +
                   std::string(kMeshRepairedFile) + "; the repair is recorded in the output");
  sub.add_option("--repair-max-deviation", options.max_deviation,
                 "With --repair: cap on the repair's Hausdorff distance from the input, fraction of the bbox "
                 "diagonal; exceeded: exit 2")
      ->default_val(options.max_deviation)
      ->check(CLI::Range(1e-9, 1.0));
}

SolidInput read_solid_input(const std::string& path, const RepairInputOptions& options,
                            const std::filesystem::path& outdir, Progress& progress) {
  const std::filesystem::path repaired_path = outdir / kMeshRepairedFile;
  SolidInput input;
  if (!options.repair) {
    input.mesh = read_closed_solid(path, progress,
                                   "; or let subfab repair it: add --repair (or run `subfab repair " + path +
                                       " -o FIXED.obj` first and look at what it changes)");
    std::error_code ec;
    std::filesystem::remove(repaired_path, ec);  // stale, from an earlier --repair run
    return input;
  }
  const Mesh raw = read_mesh_stage(path, progress);
  MeshRepairOptions repair_options;
  repair_options.max_deviation = options.max_deviation;
  repair_options.progress = &progress;
  MeshRepairResult repaired = repair_mesh(raw, repair_options);  // InvalidMeshError: exit 2
  std::filesystem::create_directories(outdir);
  const MeshRepairReport& r = repaired.report;
  if (r.changed()) {
    write_mesh(repaired.mesh, repaired_path);
    progress.warn("REPAIRED INPUT (--repair): " + r.applied_steps() + "; the result is " + repaired_path.string() +
                  ", and that is what is processed, not " + path + ": Hausdorff deviation " +
                  std::to_string(r.max_deviation) + " (" + std::to_string(r.max_deviation_fraction()) +
                  " of the diagonal, cap " + std::to_string(r.max_deviation_cap) + ")");
  } else {
    std::error_code ec;
    std::filesystem::remove(repaired_path, ec);
  }
  input.mesh = std::move(repaired.mesh);
  input.repair = r;
  return input;
}

bool parse_positive_number(const std::string& text, double& value) {
  std::size_t used = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size() && value > 0 && std::isfinite(value);
}

void remove_stale_page(const std::filesystem::path& page) {
  std::error_code ec;
  std::filesystem::remove(page, ec);
}

void write_view_or_warn(Progress& progress, const std::filesystem::path& page, const std::function<void()>& write) {
  try {
    write();
  } catch (const IoError& e) {
    remove_stale_page(page);
    progress.warn(page.filename().string() + " not written: " + e.what());
  }
}

}  // namespace subfab::cli

namespace subfab::cli {

nlohmann::ordered_json mesh_repair_record(const SolidInput& input) {
  if (!input.repair || !input.repair->changed()) return nullptr;
  nlohmann::ordered_json record = {{"mesh", kMeshRepairedFile}};
  record.update(mesh_repair_to_json(*input.repair));
  return record;
}

}  // namespace subfab::cli
