// SPDX-License-Identifier: GPL-3.0-or-later
//! \file select_cover.h
//! Minimal covering (thesis Section 4.3.2, "Minimal Covering", Eq. 4.3-4.5):
//! choose the fewest candidate boxes such that every surface triangle lies
//! entirely inside at least one chosen box, as a 0/1 integer linear program
//! solved with COIN-OR CBC.
//!
//! Outline of select_cover():
//!   1. transpose: for every face, the sorted list of boxes covering it
//!      (a face with none -> AlgorithmError naming it);
//!   2. reduce until nothing changes:
//!      - faces with the same set of boxes are one row;
//!      - a row that is a superset of another row is implied by it (dropped);
//!      - a box whose rows are a subset of another box's rows, at no lower
//!        cost, is dominated (dropped; equal sets and costs: the lower index
//!        is kept);
//!      - a row covered by a single box forces that box (its rows are dropped);
//!   3. the remaining rows x boxes go to CBC: min sum_i c_i x_i,
//!      sum_{i covers r} x_i >= 1 for every row r, x binary, with c_i = the
//!      box's cost (1 by default)
//!      (plus, optionally, a tie-break smaller than 1/2 in total that prefers
//!      boxes with a larger `preference`; CBC then stops once its best cover
//!      is within 1/2 of its bound: the total cost is proven minimal, the
//!      tie-break among covers of that cost is not), a time limit keeping the best
//!      solution found, a fixed random seed and one thread (deterministic
//!      when the time limit is not hit);
//!   4. boxes of the solution made redundant by the others are removed
//!      (only possible when the time limit stopped the search).
#pragma once

#include <cstddef>
#include <vector>

#include "subfab/core/progress.h"

namespace subfab {

//! Options of select_cover().
struct CoverOptions {
  double time_limit_s = 60.0;      // CBC wall-time limit, seconds (> 0); the best cover found is kept
  std::vector<double> preference;  // per box, >= 0 (e.g. box volume); among covers with the same
                                   // cost prefer a larger total (empty = no preference)
  std::vector<int> cost;           // per box, >= 1: blocks the box stands for (e.g. its connected
                                   // pieces, GrowResult::num_pieces); the ILP minimises the total
                                   // (empty = 1 per box, the thesis's count of boxes)
  bool verbose_solver = false;     // forward CBC's own log lines to progress->info
  Progress* progress = nullptr;    // stage reporting (nullptr = silent)
};

//! Result of select_cover().
struct CoverResult {
  std::vector<int> selected;  // indices of the chosen boxes into `covered`, increasing
  bool optimal = false;       // true when the number of boxes is proven minimal
  double lower_bound = 0;     // proven lower bound on the total cost (number of boxes with unit costs)
  std::size_t num_rows = 0;   // distinct face rows before reduction
  std::size_t num_reduced_rows = 0;   // rows left for the ILP after reduction
  std::size_t num_reduced_boxes = 0;  // box columns left for the ILP after reduction
  std::size_t num_forced = 0;         // boxes forced by a row with a single box
  double solve_time_s = 0;            // wall time spent in CBC, seconds
};

//! Minimum set cover of faces by boxes (thesis Section 4.3.2, Eq. 4.3-4.5).
//! \param covered   #B lists: covered[b] = the faces (ids in [0, num_faces))
//!                  lying entirely inside box b, sorted increasing, no repeats
//! \param num_faces number of faces F of the mesh; every face must be covered
//! \return the chosen boxes and solver statistics. Identical for identical
//!         input unless the time limit stops the solver (a warning says so).
//! \throw AlgorithmError if a face is covered by no box (names the face),
//!        or if the solver fails to find any cover (cannot happen in theory:
//!        taking all boxes is a cover).
//! \throw InvalidArgumentError on a face id out of range, unsorted lists,
//!        a preference vector of the wrong size or negative entries, or a
//!        non-positive time limit.
CoverResult select_cover(const std::vector<std::vector<int>>& covered, std::size_t num_faces,
                         const CoverOptions& options);

}  // namespace subfab
