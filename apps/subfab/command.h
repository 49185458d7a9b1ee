// SPDX-License-Identifier: GPL-3.0-or-later
//! \file command.h
//! How the `subfab` command is put together: every subcommand lives in its
//! own cmd_<name>.cpp and registers itself with a static RegisterCommand
//! built by make_command(), so adding one never touches main.cpp. What the
//! subcommands share (options, reading a solid, number parsing) is below and
//! in command.cpp.
//!
//! Exit codes (documented in the README and `subfab --help`):
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "subfab/core/parallel.h"
#include "subfab/core/progress.h"
#include "subfab/mesh/mesh.h"
#include "subfab/repair/repair_mesh.h"

namespace subfab::cli {

//! 0: success.
inline constexpr int kExitOk = 0;
//! 1: usage error (unknown option, bad value).
inline constexpr int kExitUsage = 1;
//! 2: the input cannot be used (unreadable file, not a mesh, fails the checks
//!    the command needs); the message says what is wrong and what to do.
inline constexpr int kExitBadInput = 2;
//! 3: the work ran but its result is not valid (e.g. `validate` found a
//!    failing check, or an algorithm could not reach a valid result).
inline constexpr int kExitFailed = 3;
//! 4: internal error (a bug: please report it with the input).
inline constexpr int kExitInternal = 4;

//! A registered subcommand: `setup` adds it to the app and returns the
//! subcommand and the function that runs it after parsing.
struct CommandSpec {
  std::string name;
  int order;  // position in `subfab --help`
  std::function<std::pair<CLI::App*, std::function<int()>>(CLI::App&)> setup;
};

//! Registers a subcommand at static-initialisation time.
struct RegisterCommand {
  explicit RegisterCommand(CommandSpec spec);
};

//! Options every long-running subcommand shares.
struct CommonOptions {
  int threads = 0;     // --threads: worker threads (0 = all cores)
  bool quiet = false;  // --quiet: only warnings and errors on stderr
  bool json = false;   // --json: machine-readable summary on stdout
};

//! Adds --threads, --quiet and --json to a subcommand.
void add_common_options(CLI::App& sub, CommonOptions& options);

//! Adds the required MESH argument of a command whose input must be a
//! closed solid.
void add_solid_input(CLI::App& sub, std::string& mesh);

//! Adds the required -o,--output OUTDIR option (a folder, created if needed).
void add_output_folder(CLI::App& sub, std::string& outdir);

//! True when stderr is a terminal (progress bars are drawn only then).
bool stderr_is_terminal();

//! The spec of a subcommand whose arguments are an `Args` (a struct with a
//! `CommonOptions common` member): `add_options(sub, args)` adds the
//! command's own arguments, then --threads, --quiet and --json are added;
//! after parsing, `run(args)` runs with the --threads limit in force.
template <typename Args>
CommandSpec make_command(const std::string& name, int order, const std::string& description,
                         void (*add_options)(CLI::App&, Args&), int (*run)(const Args&)) {
  return {name, order, [name, description, add_options, run](CLI::App& app) {
            auto args = std::make_shared<Args>();
            CLI::App* sub = app.add_subcommand(name, description);
            add_options(*sub, *args);
            add_common_options(*sub, args->common);
            return std::pair<CLI::App*, std::function<int()>>{sub, [args, run] {
              ThreadLimit threads(static_cast<std::size_t>(args->common.threads));
              return run(*args);
            }};
          }};
}

//! Reads the mesh at `path` in a "read" stage.
//! \throw IoError / InvalidMeshError (exit 2), with the reason.
Mesh read_mesh_stage(const std::string& path, Progress& progress);

//! Writes `mesh` to `path` in a "write" stage.
//! \throw IoError (exit 2).
void write_mesh_stage(const Mesh& mesh, const std::string& path, Progress& progress);

//! The frame of a mesh-to-mesh command (repair, smooth): reads `input`,
//! makes the result with `make(mesh)` (whose `.mesh` member is the output
//! mesh), writes it to `output`, then prints the stage timings unless
//! `quiet`. Returns what `make` returned.
template <class Make>
auto transform_mesh_file(const std::string& input, const std::string& output, ConsoleProgress& progress, bool quiet,
                         Make&& make) {
  const Mesh mesh = read_mesh_stage(input, progress);
  auto result = make(mesh);
  write_mesh_stage(result.mesh, output, progress);
  if (!quiet) progress.print_timings(std::cerr);
  return result;
}

//! Reads the mesh at `path` in a "read" stage and passes it through
//! require_closed_solid() (an inward mesh is flipped, with a warning).
//! `hint`, when not empty, is appended to a refusal (e.g. how to repair).
//! \throw IoError / InvalidMeshError (exit 2), with the reason.
Mesh read_closed_solid(const std::string& path, Progress& progress, const std::string& hint = "");

//! File name (in OUTDIR) of the solid `--repair` made of the input.
inline constexpr const char* kMeshRepairedFile = "input_mesh_repaired.obj";

//! The --repair and --repair-max-deviation options of decompose and unfold.
struct RepairInputOptions {
  bool repair = false;              // --repair: repair the input first (repair_mesh)
  double max_deviation = MeshRepairOptions{}.max_deviation;  // --repair-max-deviation, x bbox diagonal
};

//! Adds --repair and --repair-max-deviation.
void add_repair_input_options(CLI::App& sub, RepairInputOptions& options);

//! The solid a command works on, and the repair that made it (if any).
struct SolidInput {
  Mesh mesh;
  std::optional<MeshRepairReport> repair;  // set with --repair
};

//! Without --repair: read_closed_solid(), whose refusal names --repair as
//! the fix. With it: reads any mesh, repairs it (repair_mesh, with a warning
//! saying what changed and the deviation) and writes the result to
//! `outdir`/kMeshRepairedFile (removing a stale one otherwise).
//! \throw IoError / InvalidMeshError (exit 2).
//! The "mesh_repair" record of an output: null, or when --repair changed the
//! input {"mesh": kMeshRepairedFile} + mesh_repair_to_json().
nlohmann::ordered_json mesh_repair_record(const SolidInput& input);

SolidInput read_solid_input(const std::string& path, const RepairInputOptions& options,
                            const std::filesystem::path& outdir, Progress& progress);

//! Runs `write` (which writes the page `page`, e.g. OUTDIR/view.html); an
//! IoError (three.js missing, a file that cannot be written) becomes a
//! warning: the page is a by-product, the command's main output is already
//! written. A page left from an earlier run is removed then, so a folder
//! never holds a page of another result.
void write_view_or_warn(Progress& progress, const std::filesystem::path& page, const std::function<void()>& write);

//! Removes `page` if it exists (a page of an earlier run, with --no-view).
void remove_stale_page(const std::filesystem::path& page);

//! Parses the whole of `text` as a positive, finite number (std::stod's
//! syntax) into `value`; false when it is not one.
bool parse_positive_number(const std::string& text, double& value);

}  // namespace subfab::cli
