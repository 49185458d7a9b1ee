// SPDX-License-Identifier: GPL-3.0-or-later
//! \file path_builder.h
//! Private helpers of the toolpath planners: G-code rounding and a move
//! list that merges collinear moves.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "subfab/mill/toolpath.h"

namespace subfab::detail {

//! x rounded to the G-code's 0.001 mm grid (the planners compute every xy on
//! this grid, so the G-code says exactly what was checked).
double round_mm(double x);

//! z rounded up to the 0.001 mm grid (rounding never lowers the tool).
double ceil_mm(double z);

//! `n` coordinates from 0 to `length`, evenly spaced at most `spacing`
//! apart, on the 0.001 mm grid (n >= 1; one, 0, when length is 0).
std::vector<double> spaced(double length, double spacing);

//! Appends moves, merging a move into the previous one of the same kind when
//! every point so dropped lies within `tolerance` (mm) of the merged segment.
class PathBuilder {
 public:
  PathBuilder(const Vec3& start, double tolerance) : at_(start), anchor_(start), tolerance_(tolerance) {}
  void add(MoveKind kind, const Vec3& to);
  const Vec3& position() const { return at_; }
  std::vector<Move> take() { return std::move(moves_); }

 private:
  std::vector<Move> moves_;
  Vec3 at_, anchor_;
  std::vector<Vec3> merged_;  // points dropped since anchor_
  double tolerance_;
};

}  // namespace subfab::detail
