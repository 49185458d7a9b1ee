// SPDX-License-Identifier: GPL-3.0-or-later
//! \file command.h
//! How the `subfab` command is put together: every subcommand lives in its
//! own cmd_<name>.cpp and registers itself with a static RegisterCommand,
//! so adding one never touches main.cpp.
//!
//! Exit codes (documented in the README and `subfab --help`):
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <utility>

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

//! True when stderr is a terminal (progress bars are drawn only then).
bool stderr_is_terminal();

}  // namespace subfab::cli
