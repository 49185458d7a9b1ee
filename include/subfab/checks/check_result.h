// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_result.h
//! What every input check returns, and the options they share.
//! The checks themselves live one per header (check_boundary_edges.h, ...);
//! analyze_mesh() runs them all, require_closed_solid() gates the algorithms.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace subfab {

//! Outcome of one check.
enum class CheckStatus {
  Passed,   // the property holds
  Failed,   // the property does not hold: see the message
  Skipped,  // not run because an earlier problem makes it meaningless (message says which)
};

//! Kind of element a check's example ids refer to.
enum class CheckElement { Vertex, Face };

//! Result of one input check.
struct CheckResult {
  std::string name;                       // short identifier, e.g. "boundary_edges"
  CheckStatus status = CheckStatus::Passed;
  std::size_t num_offending = 0;          // offending elements (edges, faces, vertices, pairs...)
  std::size_t num_groups = 0;             // holes (boundary_edges), components (components), else 0
  CheckElement element = CheckElement::Face;  // what `examples` are ids of
  std::vector<int> examples;              // first few offending ids (0-based), ascending order
  std::string message;                    // one line: what is wrong, where, what to do

  bool passed() const { return status == CheckStatus::Passed; }
  bool failed() const { return status == CheckStatus::Failed; }
};

//! Options shared by all checks.
struct CheckOptions {
  std::size_t max_examples = 5;  // how many offending ids to keep in CheckResult::examples
};

//! "passed", "failed" or "skipped".
const char* status_name(CheckStatus status);

//! "vertex" or "face".
const char* element_name(CheckElement element);

}  // namespace subfab
