// SPDX-License-Identifier: GPL-3.0-or-later
//! \file progress.h
//! Progress reporting for long work. Algorithms take a `Progress*` in their
//! options (nullptr = silent) and report stages, counts and warnings through
//! it; they never print by themselves. The command-line front end passes a
//! ConsoleProgress, which writes to stderr, draws a bar when stderr is a
//! terminal and prints a per-stage time table at the end.
#pragma once

#include <chrono>
#include <cstddef>
#include <iosfwd>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace subfab {

//! Receiver of progress events. Every method may be called from worker
//! threads concurrently; implementations must be thread-safe.
class Progress {
 public:
  virtual ~Progress() = default;
  //! A named stage starts (stages do not nest).
  virtual void begin_stage(std::string_view name) {}
  //! `done` of `total` work items of the current stage are finished.
  virtual void update(std::size_t done, std::size_t total) {}
  //! An informational line ("12 boxes grown").
  virtual void info(std::string_view text) {}
  //! A warning the user should read (mesh was refined, solver hit its limit).
  virtual void warn(std::string_view text) {}
  //! The current stage ends.
  virtual void end_stage() {}
};

//! RAII helper: begin_stage on construction, end_stage on destruction.
//! Accepts nullptr (then does nothing).
class StageScope {
 public:
  StageScope(Progress* progress, std::string_view name) : progress_(progress) {
    if (progress_) progress_->begin_stage(name);
  }
  ~StageScope() {
    if (progress_) progress_->end_stage();
  }
  StageScope(const StageScope&) = delete;
  StageScope& operator=(const StageScope&) = delete;

 private:
  Progress* progress_;
};

//! Writes progress to a stream (stderr in the command), with a live bar when
//! the stream is a terminal, and keeps the wall time of every stage.
class ConsoleProgress final : public Progress {
 public:
  //! \param out      where to write (normally std::cerr)
  //! \param quiet    only warnings are written
  //! \param terminal draw a live progress bar (pass isatty(2))
  ConsoleProgress(std::ostream& out, bool quiet, bool terminal);
  void begin_stage(std::string_view name) override;
  void update(std::size_t done, std::size_t total) override;
  void info(std::string_view text) override;
  void warn(std::string_view text) override;
  void end_stage() override;

  //! Wall time of each finished stage in seconds, in the order they ran
  //! (a stage that ran twice appears twice).
  std::vector<std::pair<std::string, double>> timings() const;
  //! Prints the stage/time table (and the total).
  void print_timings(std::ostream& out) const;
  //! Warnings seen so far, in order.
  std::vector<std::string> warnings() const;

 private:
  void clear_bar_locked();
  std::ostream& out_;
  bool quiet_;
  bool terminal_;
  mutable std::mutex mutex_;
  std::string stage_;  // the innermost open stage ("" when none)
  std::vector<std::pair<std::string, std::chrono::steady_clock::time_point>> open_;  // open stages, outermost first
  std::chrono::steady_clock::time_point last_draw_;
  bool bar_visible_ = false;
  std::vector<std::pair<std::string, double>> timings_;
  std::vector<std::string> warnings_;
};

}  // namespace subfab
