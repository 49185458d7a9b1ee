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

namespace subfab::cli {

void add_common_options(CLI::App& sub, CommonOptions& options) {
  sub.add_option("--threads", options.threads, "Worker threads (0 = all cores); results do not depend on it")
      ->default_val(0)
      ->check(CLI::NonNegativeNumber);
  sub.add_flag("--quiet,-q", options.quiet, "Print only warnings and errors on stderr");
  sub.add_flag("--json", options.json, "Print a machine-readable summary as JSON on stdout");
}

void add_solid_input(CLI::App& sub, std::string& mesh) {
  sub.add_option("MESH", mesh, "Input mesh (.obj .off .ply .stl), a closed solid")->required();
}

void add_output_folder(CLI::App& sub, std::string& outdir) {
  sub.add_option("-o,--output", outdir, "Output folder (created if needed)")->required();
}

bool stderr_is_terminal() { return isatty(STDERR_FILENO) == 1; }

Mesh read_closed_solid(const std::string& path, Progress& progress) {
  StageScope stage(&progress, "read");
  Mesh mesh = read_mesh(path);            // IoError / InvalidMeshError: exit 2
  require_closed_solid(mesh, &progress);  // InvalidMeshError: exit 2, with the reason
  return mesh;
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
