// SPDX-License-Identifier: GPL-3.0-or-later
// Minimal covering as a 0/1 ILP with COIN-OR CBC (thesis Section 4.3.2).
#include "subfab/decompose/select_cover.h"

#include <algorithm>
#include <cstdint>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <string>

#include <coin/CbcModel.hpp>
#include <coin/CbcSolver.hpp>
#include <coin/CoinMessageHandler.hpp>
#include <coin/CoinPackedMatrix.hpp>
#include <coin/OsiClpSolverInterface.hpp>

#include "subfab/core/error.h"

namespace subfab {
namespace {

using IdList = std::vector<int>;

//! True when sorted `a` is a subset of sorted `b`.
bool is_subset(const IdList& a, const IdList& b) {
  if (a.size() > b.size()) return false;
  return std::includes(b.begin(), b.end(), a.begin(), a.end());
}

//! The reduced set-cover instance: rows (distinct face sets) x boxes, each
//! side stored as sorted id lists, with activity flags.
struct Instance {
  std::vector<IdList> row_boxes;    // per row: the boxes covering it
  std::vector<int> row_face;        // per row: one face of the row (for messages)
  std::vector<char> row_active;
  std::vector<IdList> box_rows;     // per box: the rows it covers
  std::vector<char> box_active;     // candidate for the ILP
  std::vector<char> box_forced;     // chosen by reduction
  std::vector<int> box_cost;        // per box, >= 1

  //! Recomputes the lists restricted to active rows and boxes.
  void compact() {
    for (std::size_t r = 0; r < row_boxes.size(); ++r) {
      if (!row_active[r]) {
        row_boxes[r].clear();
        continue;
      }
      std::erase_if(row_boxes[r], [&](int b) { return !box_active[static_cast<std::size_t>(b)]; });
    }
    for (std::size_t b = 0; b < box_rows.size(); ++b) {
      if (!box_active[b]) {
        box_rows[b].clear();
        continue;
      }
      std::erase_if(box_rows[b], [&](int r) { return !row_active[static_cast<std::size_t>(r)]; });
    }
  }

  //! A row covered by a single active box forces it. Returns true on change.
  bool force_single_rows() {
    bool changed = false;
    for (std::size_t r = 0; r < row_boxes.size(); ++r) {
      if (!row_active[r] || row_boxes[r].size() != 1) continue;
      const int b = row_boxes[r][0];
      box_forced[static_cast<std::size_t>(b)] = 1;
      box_active[static_cast<std::size_t>(b)] = 0;
      for (int rr : box_rows[static_cast<std::size_t>(b)]) row_active[static_cast<std::size_t>(rr)] = 0;
      changed = true;
    }
    if (changed) compact();
    return changed;
  }

  //! Drops every row that is a superset of another active row (equal rows:
  //! the lower index is kept). Returns true on change.
  bool drop_implied_rows() {
    std::vector<char> drop(row_boxes.size(), 0);
    // Each row's boxes as a bitset: a subset test in a few word operations
    // (egea's 7715 rows after a tolerance: 0.8 s with sorted lists).
    const std::size_t words = (box_rows.size() + 63) / 64;
    std::vector<std::uint64_t> bits(row_boxes.size() * words, 0);
    for (std::size_t r = 0; r < row_boxes.size(); ++r)
      for (int b : row_boxes[r])
        bits[r * words + (static_cast<std::size_t>(b) >> 6)] |= std::uint64_t{1} << (static_cast<unsigned>(b) & 63u);
    const auto row_in = [&](std::size_t small, std::size_t big) {
      const std::uint64_t* a = &bits[small * words];
      const std::uint64_t* b = &bits[big * words];
      for (std::size_t w = 0; w < words; ++w)
        if (a[w] & ~b[w]) return false;
      return true;
    };
    for (std::size_t s = 0; s < row_boxes.size(); ++s) {
      if (!row_active[s]) continue;
      const IdList& small = row_boxes[s];
      // Every superset row contains the rarest box of `small`.
      int rarest = small[0];
      for (int b : small)
        if (box_rows[static_cast<std::size_t>(b)].size() < box_rows[static_cast<std::size_t>(rarest)].size()) rarest = b;
      for (int r_int : box_rows[static_cast<std::size_t>(rarest)]) {
        const auto r = static_cast<std::size_t>(r_int);
        if (r == s || drop[r] || drop[s]) continue;
        const IdList& big = row_boxes[r];
        if (small.size() > big.size() || !row_in(s, r)) continue;
        if (small.size() == big.size() && r < s) continue;  // equal: keep the lower index r
        drop[r] = 1;
      }
    }
    bool changed = false;
    for (std::size_t r = 0; r < drop.size(); ++r)
      if (drop[r]) {
        row_active[r] = 0;
        changed = true;
      }
    if (changed) compact();
    return changed;
  }

  //! Drops every box whose rows are a subset of another active box's rows
  //! with a cost no higher (equal sets and costs: the lower index is kept),
  //! and boxes with no rows. The relation "subset and no higher cost, one of
  //! them strict, or both equal with a higher index" is a strict partial
  //! order, so every dropped box has a kept dominator. Returns true on change.
  bool drop_dominated_boxes() {
    std::vector<char> drop(box_rows.size(), 0);
    for (std::size_t i = 0; i < box_rows.size(); ++i) {
      if (!box_active[i]) continue;
      const IdList& mine = box_rows[i];
      if (mine.empty()) {
        drop[i] = 1;
        continue;
      }
      int rarest = mine[0];
      for (int r : mine)
        if (row_boxes[static_cast<std::size_t>(r)].size() < row_boxes[static_cast<std::size_t>(rarest)].size()) rarest = r;
      for (int j_int : row_boxes[static_cast<std::size_t>(rarest)]) {
        const auto j = static_cast<std::size_t>(j_int);
        if (j == i) continue;
        const IdList& other = box_rows[j];
        if (box_cost[j] > box_cost[i] || !is_subset(mine, other)) continue;
        if (mine.size() == other.size() && box_cost[j] == box_cost[i] && j > i) continue;  // equal: keep the lower index i
        drop[i] = 1;
        break;
      }
    }
    bool changed = false;
    for (std::size_t b = 0; b < drop.size(); ++b)
      if (drop[b]) {
        box_active[b] = 0;
        changed = true;
      }
    if (changed) compact();
    return changed;
  }
};

//! Forwards CBC's messages to Progress::info (verbose mode) or swallows them.
class ProgressMessageHandler : public CoinMessageHandler {
 public:
  explicit ProgressMessageHandler(Progress* progress) : progress_(progress) {}
  ProgressMessageHandler(const ProgressMessageHandler&) = default;
  CoinMessageHandler* clone() const override { return new ProgressMessageHandler(*this); }
  int print() override {
    if (progress_) progress_->info(std::string("cbc: ") + messageBuffer());
    return 0;
  }

 private:
  Progress* progress_;
};

int cbc_no_callback(CbcModel*, int) { return 0; }

struct IlpSolution {
  std::vector<int> chosen;  // column indices with x = 1
  bool optimal = false;
  double lower_bound = 0;   // on the total cost of the columns chosen
  bool time_limit_hit = false;
};

//! Solves min sum c_j x_j s.t. every row has a chosen column, x binary.
IlpSolution solve_ilp(const std::vector<IdList>& rows, std::size_t num_cols, const std::vector<double>& costs,
                      bool integral_costs, const CoverOptions& options) {
  // Row-ordered, built at once (appending row by row copies the whole
  // matrix as it grows: most of the cover's time on egea's 7715 rows).
  std::vector<CoinBigIndex> starts;
  std::vector<int> lengths, indices;
  starts.reserve(rows.size());
  lengths.reserve(rows.size());
  for (const IdList& row : rows) {
    starts.push_back(static_cast<CoinBigIndex>(indices.size()));
    lengths.push_back(static_cast<int>(row.size()));
    indices.insert(indices.end(), row.begin(), row.end());
  }
  const std::vector<double> ones(indices.size(), 1.0);
  const CoinPackedMatrix matrix(false, static_cast<int>(num_cols), static_cast<int>(rows.size()),
                                static_cast<CoinBigIndex>(indices.size()), ones.data(), indices.data(), starts.data(),
                                lengths.data());
  const std::vector<double> col_lb(num_cols, 0.0), col_ub(num_cols, 1.0);
  const std::vector<double> row_lb(rows.size(), 1.0), row_ub(rows.size(), COIN_DBL_MAX);

  OsiClpSolverInterface solver;
  ProgressMessageHandler handler(options.verbose_solver ? options.progress : nullptr);
  solver.passInMessageHandler(&handler);
  solver.messageHandler()->setLogLevel(options.verbose_solver ? 1 : 0);
  solver.loadProblem(matrix, col_lb.data(), col_ub.data(), costs.data(), row_lb.data(), row_ub.data());
  for (std::size_t j = 0; j < num_cols; ++j) solver.setInteger(static_cast<int>(j));

  CbcModel model(solver);
  model.passInMessageHandler(&handler);
  CbcSolverUsefulData data;
  data.noPrinting_ = !options.verbose_solver;
  data.useSignalHandler_ = false;
  CbcMain0(model, data);

  char seconds[64];
  std::snprintf(seconds, sizeof seconds, "%.6g", options.time_limit_s);
  std::vector<const char*> argv = {"subfab-cover", "-log", options.verbose_solver ? "1" : "0",
                                   "-slog", "0", "-seconds", seconds, "-randomCbcSeed", "12345",
                                   "-randomSeed", "12345", "-threads", "0"};
  // With unit costs the objective is integral, so CBC may prune any node
  // that cannot improve by a whole box.
  if (integral_costs) {
    argv.push_back("-increment");
    argv.push_back("0.999");
  } else {
    // The tie-break adds less than 1/2 to any solution (select_cover()):
    // once the best cover found is within 1/2 of the bound, no cover with a
    // box fewer exists, so the number of boxes is proven minimal; the
    // tie-break among covers of that size is not proven best (egea at
    // 8.3e-2: a 5833-row cover took 42 s of branch and bound on it).
    argv.push_back("-allowableGap");
    argv.push_back("0.4999");
  }
  argv.push_back("-solve");
  argv.push_back("-quit");
  CbcMain1(static_cast<int>(argv.size()), argv.data(), model, cbc_no_callback, data);

  IlpSolution out;
  const double* x = model.bestSolution();
  if (x == nullptr) return out;  // no solution at all (caller reports)
  for (std::size_t j = 0; j < num_cols; ++j)
    if (x[j] > 0.5) out.chosen.push_back(static_cast<int>(j));
  out.optimal = model.isProvenOptimal();
  out.time_limit_hit = model.isSecondsLimitReached();
  out.lower_bound = model.getBestPossibleObjValue();
  return out;
}

void validate_input(const std::vector<std::vector<int>>& covered, std::size_t num_faces,
                    const CoverOptions& options) {
  if (!(options.time_limit_s > 0))
    throw InvalidArgumentError("select_cover: time limit must be positive, got " +
                               std::to_string(options.time_limit_s) + " s");
  if (!options.preference.empty() && options.preference.size() != covered.size())
    throw InvalidArgumentError("select_cover: " + std::to_string(options.preference.size()) +
                               " preference values for " + std::to_string(covered.size()) + " boxes");
  for (double p : options.preference)
    if (!(p >= 0) || !std::isfinite(p))
      throw InvalidArgumentError("select_cover: box preferences must be finite and non-negative");
  if (!options.cost.empty() && options.cost.size() != covered.size())
    throw InvalidArgumentError("select_cover: " + std::to_string(options.cost.size()) + " costs for " +
                               std::to_string(covered.size()) + " boxes");
  for (int c : options.cost)
    if (c < 1) throw InvalidArgumentError("select_cover: box costs must be at least 1");
  for (std::size_t b = 0; b < covered.size(); ++b) {
    const IdList& faces = covered[b];
    for (std::size_t k = 0; k < faces.size(); ++k) {
      if (faces[k] < 0 || static_cast<std::size_t>(faces[k]) >= num_faces)
        throw InvalidArgumentError("select_cover: box " + std::to_string(b) + " lists face " +
                                   std::to_string(faces[k]) + ", outside [0, " + std::to_string(num_faces) + ")");
      if (k > 0 && faces[k - 1] >= faces[k])
        throw InvalidArgumentError("select_cover: the face list of box " + std::to_string(b) +
                                   " is not sorted increasing without repeats");
    }
  }
}

}  // namespace

CoverResult select_cover(const std::vector<std::vector<int>>& covered, std::size_t num_faces,
                         const CoverOptions& options) {
  validate_input(covered, num_faces, options);
  const std::size_t num_boxes = covered.size();
  CoverResult result;
  if (num_faces == 0) return result;

  // 1. Transpose and group faces with the same set of boxes into rows.
  std::vector<IdList> face_boxes(num_faces);
  for (std::size_t b = 0; b < num_boxes; ++b)
    for (int f : covered[b]) face_boxes[static_cast<std::size_t>(f)].push_back(static_cast<int>(b));
  std::size_t num_uncovered = 0;
  int first_uncovered = -1;
  for (std::size_t f = 0; f < num_faces; ++f)
    if (face_boxes[f].empty()) {
      if (num_uncovered++ == 0) first_uncovered = static_cast<int>(f);
    }
  if (num_uncovered > 0)
    throw AlgorithmError("minimal cover: face " + std::to_string(first_uncovered) + " (and " +
                         std::to_string(num_uncovered - 1) +
                         " more) lies inside no candidate box; box growth must cover every face");

  Instance inst;
  {
    std::map<IdList, int> row_of;
    for (std::size_t f = 0; f < num_faces; ++f) {
      auto [it, inserted] = row_of.try_emplace(face_boxes[f], static_cast<int>(inst.row_boxes.size()));
      if (inserted) {
        inst.row_boxes.push_back(face_boxes[f]);
        inst.row_face.push_back(static_cast<int>(f));
      }
    }
  }
  const std::size_t num_rows = inst.row_boxes.size();
  result.num_rows = num_rows;
  inst.row_active.assign(num_rows, 1);
  inst.box_rows.assign(num_boxes, {});
  for (std::size_t r = 0; r < num_rows; ++r)
    for (int b : inst.row_boxes[r]) inst.box_rows[static_cast<std::size_t>(b)].push_back(static_cast<int>(r));
  inst.box_active.assign(num_boxes, 1);
  inst.box_forced.assign(num_boxes, 0);
  inst.box_cost = options.cost.empty() ? std::vector<int>(num_boxes, 1) : options.cost;
  inst.compact();

  // 2. Reduce to a fixed point.
  for (bool changed = true; changed;) {
    changed = inst.force_single_rows();
    changed = inst.drop_implied_rows() || changed;
    changed = inst.drop_dominated_boxes() || changed;
  }

  std::vector<char> chosen = inst.box_forced;
  result.num_forced = static_cast<std::size_t>(std::count(chosen.begin(), chosen.end(), 1));

  // 3. ILP on what is left.
  std::vector<int> col_box;  // ILP column -> box
  std::vector<int> box_col(num_boxes, -1);
  for (std::size_t b = 0; b < num_boxes; ++b)
    if (inst.box_active[b]) {
      box_col[b] = static_cast<int>(col_box.size());
      col_box.push_back(static_cast<int>(b));
    }
  std::vector<IdList> ilp_rows;
  for (std::size_t r = 0; r < num_rows; ++r) {
    if (!inst.row_active[r]) continue;
    IdList row;
    for (int b : inst.row_boxes[r]) row.push_back(box_col[static_cast<std::size_t>(b)]);
    ilp_rows.push_back(std::move(row));
  }
  result.num_reduced_rows = ilp_rows.size();
  result.num_reduced_boxes = col_box.size();
  result.optimal = true;
  for (std::size_t b = 0; b < num_boxes; ++b)
    if (chosen[b]) result.lower_bound += inst.box_cost[b];

  if (!ilp_rows.empty()) {
    // Costs: the box's cost (1 by default), minus a tie-break below
    // 1/(2 (n+1)) per box, so that the whole tie-break of any solution stays
    // below 1/2 and never trades against the (integral) total cost.
    std::vector<double> costs(col_box.size(), 1.0);
    for (std::size_t j = 0; j < col_box.size(); ++j)
      costs[j] = inst.box_cost[static_cast<std::size_t>(col_box[j])];
    bool integral = true;
    if (!options.preference.empty()) {
      double max_pref = 0;
      for (int b : col_box) max_pref = std::max(max_pref, options.preference[static_cast<std::size_t>(b)]);
      if (max_pref > 0) {
        const double eps = 0.5 / static_cast<double>(col_box.size() + 1);
        for (std::size_t j = 0; j < col_box.size(); ++j)
          costs[j] -= eps * options.preference[static_cast<std::size_t>(col_box[j])] / max_pref;
        integral = false;
      }
    }
    const auto start = std::chrono::steady_clock::now();
    const IlpSolution ilp = solve_ilp(ilp_rows, col_box.size(), costs, integral, options);
    result.solve_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (ilp.chosen.empty())
      throw AlgorithmError("minimal cover: CBC found no cover of " + std::to_string(ilp_rows.size()) +
                           " rows by " + std::to_string(col_box.size()) + " boxes within " +
                           std::to_string(options.time_limit_s) + " s; raise the time limit");
    for (int j : ilp.chosen) chosen[static_cast<std::size_t>(col_box[static_cast<std::size_t>(j)])] = 1;
    result.optimal = ilp.optimal;
    // The tie-break lowers the objective by less than 1/2: round the bound up
    // to whole boxes.
    result.lower_bound += std::max(0.0, std::ceil(ilp.lower_bound - 0.5 - 1e-9));
    if (options.progress) {
      double found = 0;
      for (int j : ilp.chosen) found += inst.box_cost[static_cast<std::size_t>(col_box[static_cast<std::size_t>(j)])];
      const double bound = std::max(0.0, std::ceil(ilp.lower_bound - 0.5 - 1e-9));
      const double gap = found > 0 ? (found - bound) / found : 0.0;
      char line[256];
      std::snprintf(line, sizeof line, "cover ILP: %zu rows x %zu boxes, %zu chosen (+%zu forced), bound %.0f, gap %.1f%%%s, %.2f s",
                    ilp_rows.size(), col_box.size(), ilp.chosen.size(), result.num_forced, bound, 100.0 * gap,
                    ilp.optimal ? " (optimal)" : "", result.solve_time_s);
      options.progress->info(line);
      if (ilp.time_limit_hit && !ilp.optimal)
        options.progress->warn("minimal cover: CBC stopped at the time limit (" +
                               std::to_string(options.time_limit_s) +
                               " s) with a gap; the cover may use more boxes than necessary");
    }
  }

  // 4. Drop boxes made redundant by the others (smallest preference, then
  // fewest faces, first), then check the cover against the input.
  std::vector<int> count(num_faces, 0);
  std::vector<int> order;
  for (std::size_t b = 0; b < num_boxes; ++b)
    if (chosen[b]) {
      order.push_back(static_cast<int>(b));
      for (int f : covered[b]) ++count[static_cast<std::size_t>(f)];
    }
  auto pref = [&](int b) { return options.preference.empty() ? 0.0 : options.preference[static_cast<std::size_t>(b)]; };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    if (pref(a) != pref(b)) return pref(a) < pref(b);
    return covered[static_cast<std::size_t>(a)].size() < covered[static_cast<std::size_t>(b)].size();
  });
  for (int b : order) {
    const IdList& faces = covered[static_cast<std::size_t>(b)];
    if (std::all_of(faces.begin(), faces.end(), [&](int f) { return count[static_cast<std::size_t>(f)] > 1; })) {
      chosen[static_cast<std::size_t>(b)] = 0;
      for (int f : faces) --count[static_cast<std::size_t>(f)];
    }
  }
  for (std::size_t f = 0; f < num_faces; ++f)
    if (count[f] == 0)  // a bug, not a user error: keep the message precise
      throw AlgorithmError("minimal cover: internal error, face " + std::to_string(f) + " left uncovered");
  for (std::size_t b = 0; b < num_boxes; ++b)
    if (chosen[b]) result.selected.push_back(static_cast<int>(b));
  return result;
}

}  // namespace subfab
