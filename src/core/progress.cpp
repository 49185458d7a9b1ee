// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/core/progress.h"

#include <cstdio>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace subfab {

ConsoleProgress::ConsoleProgress(std::ostream& out, bool quiet, bool terminal)
    : out_(out), quiet_(quiet), terminal_(terminal) {}

void ConsoleProgress::clear_bar_locked() {
  if (bar_visible_) {
    out_ << "\r\033[K";
    bar_visible_ = false;
  }
}

void ConsoleProgress::begin_stage(std::string_view name) {
  std::lock_guard<std::mutex> lock(mutex_);
  stage_ = std::string(name);
  open_.emplace_back(stage_, std::chrono::steady_clock::now());
  last_draw_ = {};
  if (!quiet_) out_ << "[" << stage_ << "] ..." << std::endl;
}

void ConsoleProgress::update(std::size_t done, std::size_t total) {
  if (quiet_ || !terminal_ || total == 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  if (done < total && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  constexpr int kWidth = 30;
  const double fraction = std::min(1.0, static_cast<double>(done) / static_cast<double>(total));
  const int filled = static_cast<int>(fraction * kWidth);
  std::ostringstream bar;
  bar << "\r\033[K[" << stage_ << "] [" << std::string(filled, '#')
      << std::string(kWidth - filled, '.') << "] " << done << "/" << total;
  out_ << bar.str() << std::flush;
  bar_visible_ = true;
}

void ConsoleProgress::info(std::string_view text) {
  if (quiet_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  clear_bar_locked();
  out_ << "[" << (stage_.empty() ? "subfab" : stage_) << "] " << text << std::endl;
}

void ConsoleProgress::warn(std::string_view text) {
  std::lock_guard<std::mutex> lock(mutex_);
  clear_bar_locked();
  warnings_.emplace_back(text);
  out_ << "warning: " << text << std::endl;
}

void ConsoleProgress::end_stage() {
  std::lock_guard<std::mutex> lock(mutex_);
  clear_bar_locked();
  if (open_.empty()) return;  // unbalanced: nothing open
  // stages nest (the sliver stage runs merges within the tolerance): the
  // innermost one ends, the one around it is current again
  const auto [name, start] = open_.back();
  open_.pop_back();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  timings_.emplace_back(name, seconds);
  if (!quiet_) {
    std::ostringstream line;
    line << "[" << name << "] done in " << std::fixed << std::setprecision(2) << seconds << " s";
    out_ << line.str() << std::endl;
  }
  stage_ = open_.empty() ? std::string() : open_.back().first;
}

std::vector<std::pair<std::string, double>> ConsoleProgress::timings() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return timings_;
}

std::vector<std::string> ConsoleProgress::warnings() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return warnings_;
}

void ConsoleProgress::print_timings(std::ostream& out) const {
  const auto rows = timings();
  std::size_t width = 5;
  for (const auto& [name, s] : rows) width = std::max(width, name.size());
  double total = 0;
  std::ostringstream table;
  table << std::left << std::setw(static_cast<int>(width)) << "stage" << "  " << std::right
        << std::setw(10) << "time (s)" << "\n";
  for (const auto& [name, s] : rows) {
    table << std::left << std::setw(static_cast<int>(width)) << name << "  " << std::right
          << std::setw(10) << std::fixed << std::setprecision(3) << s << "\n";
    total += s;
  }
  table << std::left << std::setw(static_cast<int>(width)) << "total" << "  " << std::right
        << std::setw(10) << std::fixed << std::setprecision(3) << total << "\n";
  out << table.str();
}

}  // namespace subfab
