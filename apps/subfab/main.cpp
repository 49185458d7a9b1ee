// SPDX-License-Identifier: GPL-3.0-or-later
//! subfab: geometry processing for subtractive fabrication (command line).
//! Thin front end: parses arguments, runs a library algorithm, maps typed
//! errors to exit codes (see command.h).
#include <algorithm>
#include <iostream>
#include <new>
#include <vector>

#include "command.h"
#include "subfab/core/error.h"

namespace subfab::cli {
namespace {
std::vector<CommandSpec>& registry() {
  static std::vector<CommandSpec> commands;
  return commands;
}

//! Prints "error: <what>" on stderr and returns `exit_code`.
int report_error(const std::exception& e, int exit_code) {
  std::cerr << "error: " << e.what() << "\n";
  return exit_code;
}
}  // namespace

RegisterCommand::RegisterCommand(CommandSpec spec) { registry().push_back(std::move(spec)); }

}  // namespace subfab::cli

int main(int argc, char** argv) {
  using namespace subfab::cli;
  CLI::App app{
      "subfab: turns 3D models into parts a 3-axis CNC milling machine can make.\n\n"
      "Exit codes: 0 success, 1 usage error, 2 unusable input (the message says why),\n"
      "3 result failed validation, 4 internal error.",
      "subfab"};
  app.set_version_flag("--version", std::string("subfab 0.1.0"));
  app.require_subcommand(1);

  auto specs = registry();
  std::sort(specs.begin(), specs.end(),
            [](const CommandSpec& a, const CommandSpec& b) { return a.order < b.order; });
  std::vector<std::pair<CLI::App*, std::function<int()>>> commands;
  for (const auto& spec : specs) commands.push_back(spec.setup(app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }

  try {
    for (auto& [sub, run] : commands)
      if (sub->parsed()) return run();
    return kExitUsage;
  } catch (const subfab::InvalidArgumentError& e) {
    return report_error(e, kExitUsage);
  } catch (const subfab::IoError& e) {
    return report_error(e, kExitBadInput);
  } catch (const subfab::InvalidMeshError& e) {
    return report_error(e, kExitBadInput);
  } catch (const subfab::AlgorithmError& e) {
    return report_error(e, kExitFailed);
  } catch (const std::bad_alloc&) {
    std::cerr << "error: out of memory; try a smaller model, a coarser grid or fewer threads\n";
    return kExitFailed;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what()
              << "\nThis is a bug in subfab; please report it with the input file and command.\n";
    return kExitInternal;
  }
}
