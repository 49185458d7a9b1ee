// SPDX-License-Identifier: GPL-3.0-or-later
//! \file export_format.h
//! Private: number formatting and file opening shared by the writers of the
//! unfolding export (stage 7, after thesis Chapter 3; Section 3.4 leaves
//! fabrication output as future work).
#pragma once

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "subfab/core/error.h"

namespace subfab::unfold_detail {

//! x with 17 significant digits (round-trips a double).
inline std::string num(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

//! x with 6 significant digits (angles, messages).
inline std::string short_num(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

//! Opens `path` for writing. \throw IoError when it cannot be opened.
inline std::ofstream open_out(const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw IoError("cannot write " + path.string() + ": check that the folder is writable");
  return out;
}

}  // namespace subfab::unfold_detail
