// SPDX-License-Identifier: GPL-3.0-or-later
// Block snapping and shrinking (thesis Section 4.3.4).
#include "subfab/decompose/snap_and_shrink.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>
#include <string>
#include <tuple>

#include "decompose/snap_and_shrink_detail.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab::detail {
namespace {

//! Do the open intervals of a and b intersect along every dimension but k?
bool overlap_across(const Box3& a, const Box3& b, int k) {
  for (int c = 0; c < 3; ++c)
    if (c != k && !(a.min[c] < b.max[c] && b.min[c] < a.max[c])) return false;
  return true;
}

bool has_volume(const Box3& b) { return (b.min.array() < b.max.array()).all(); }
bool contains_box(const Box3& outer, const Box3& inner) {
  return (outer.min.array() <= inner.min.array()).all() && (inner.max.array() <= outer.max.array()).all();
}

double& face_coordinate(Box3& b, int k, int side) { return side > 0 ? b.max[k] : b.min[k]; }
double face_coordinate(const Box3& b, int k, int side) { return side > 0 ? b.max[k] : b.min[k]; }

//! Boxes with their covered faces and the per-face cover counts.
class CoverState {
 public:
  CoverState(const SolidIndex& index, std::vector<HeightBox> boxes, double max_height, const Vec3& machine)
      : index_(index), boxes_(std::move(boxes)), max_height_(max_height), machine_(machine) {
    covered_.resize(boxes_.size());
    parallel_for(0, boxes_.size(), [&](std::size_t b) { covered_[b] = index_.faces_covered(boxes_[b]); });
    count_.assign(static_cast<std::size_t>(index_.num_faces()), 0);
    for (const auto& list : covered_)
      for (int f : list) ++count_[static_cast<std::size_t>(f)];
  }

  const std::vector<HeightBox>& boxes() const { return boxes_; }
  std::vector<HeightBox> release() { return std::move(boxes_); }

  //! Replaces box b by `box` if it has a volume, is valid (checked unless it
  //! lies inside the old box) and every face b covered stays covered.
  bool try_replace(std::size_t b, const Box3& box) {
    if (!has_volume(box)) return false;
    const Axis axis = boxes_[b].axis;
    // A move may enlarge the box: it must still respect the size limits.
    if (!contains_box(boxes_[b].box, box) && !box_fits_limits(box, axis, max_height_, machine_)) return false;
    if (!contains_box(boxes_[b].box, box) && !index_.box_is_valid(box, axis)) return false;
    std::vector<int> now = index_.faces_covered(box, axis);
    std::vector<int> lost, gained;
    std::set_difference(covered_[b].begin(), covered_[b].end(), now.begin(), now.end(), std::back_inserter(lost));
    for (int f : lost)
      if (count_[static_cast<std::size_t>(f)] <= 1) return false;
    std::set_difference(now.begin(), now.end(), covered_[b].begin(), covered_[b].end(), std::back_inserter(gained));
    for (int f : lost) --count_[static_cast<std::size_t>(f)];
    for (int f : gained) ++count_[static_cast<std::size_t>(f)];
    covered_[b] = std::move(now);
    boxes_[b].box = box;
    return true;
  }

 private:
  const SolidIndex& index_;
  std::vector<HeightBox> boxes_;
  std::vector<std::vector<int>> covered_;
  std::vector<int> count_;
  double max_height_;
  Vec3 machine_;
};

struct SnapCandidate {
  double distance;
  int i, j, k, si, sj;  // face (i, k, si) and face (j, k, sj)
  auto key() const { return std::make_tuple(distance, i, j, k, si, sj); }
};

int snap_faces(CoverState& state, double snap_distance) {
  const auto& boxes = state.boxes();
  const int n = static_cast<int>(boxes.size());
  std::vector<SnapCandidate> candidates;
  auto close = [&](double a, double b) { return a != b && std::abs(a - b) < snap_distance; };
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = 0; k < 3; ++k) {
        const Box3& a = boxes[static_cast<std::size_t>(i)].box;
        const Box3& b = boxes[static_cast<std::size_t>(j)].box;
        if (!overlap_across(a, b, k)) continue;
        for (int si : {-1, 1})
          for (int sj : {-1, 1}) {
            const double ca = face_coordinate(a, k, si), cb = face_coordinate(b, k, sj);
            if (close(ca, cb)) candidates.push_back({std::abs(ca - cb), i, j, k, si, sj});
          }
      }
  std::sort(candidates.begin(), candidates.end(),
            [](const SnapCandidate& x, const SnapCandidate& y) { return x.key() < y.key(); });

  std::set<std::tuple<int, int, int>> locked;  // aligned faces (box, k, side)
  int num_snapped = 0;
  for (const SnapCandidate& c : candidates) {
    const Box3& a = boxes[static_cast<std::size_t>(c.i)].box;
    const Box3& b = boxes[static_cast<std::size_t>(c.j)].box;
    const double ca = face_coordinate(a, c.k, c.si), cb = face_coordinate(b, c.k, c.sj);
    if (!close(ca, cb) || !overlap_across(a, b, c.k)) continue;  // changed by an earlier snap
    // Move face (box, side) to `target`; enlarging moves first.
    struct Move {
      int box, side;
      double target;
      bool enlarges;
    };
    Move moves[2] = {{c.i, c.si, cb, c.si > 0 ? cb > ca : cb < ca}, {c.j, c.sj, ca, c.sj > 0 ? ca > cb : ca < cb}};
    if (!moves[0].enlarges && moves[1].enlarges) std::swap(moves[0], moves[1]);
    for (const Move& m : moves) {
      if (locked.count({m.box, c.k, m.side})) continue;
      Box3 moved = boxes[static_cast<std::size_t>(m.box)].box;
      face_coordinate(moved, c.k, m.side) = m.target;
      if (state.try_replace(static_cast<std::size_t>(m.box), moved)) {
        locked.insert({c.i, c.k, c.si});
        locked.insert({c.j, c.k, c.sj});
        ++num_snapped;
        break;
      }
    }
  }
  return num_snapped;
}

int shrink_overlaps(CoverState& state, int max_passes) {
  const auto& boxes = state.boxes();
  const std::size_t n = boxes.size();
  int num_shrunk = 0;
  for (int pass = 0; pass < max_passes; ++pass) {
    bool changed = false;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        if (!boxes[i].box.overlaps(boxes[j].box)) continue;
        // Trims that remove the whole overlap: one face of one box onto the
        // other box's opposite face. Smallest removed volume first.
        struct Trim {
          double removed;
          std::size_t box;
          Box3 result;
        };
        std::vector<Trim> trims;
        for (const auto& [x, y] : {std::pair{i, j}, std::pair{j, i}}) {
          const Box3& bx = boxes[x].box;
          const Box3& by = boxes[y].box;
          for (int k = 0; k < 3; ++k) {
            if (by.min[k] > bx.min[k]) {
              Box3 t = bx;
              t.max[k] = by.min[k];
              trims.push_back({bx.volume() - t.volume(), x, t});
            }
            if (by.max[k] < bx.max[k]) {
              Box3 t = bx;
              t.min[k] = by.max[k];
              trims.push_back({bx.volume() - t.volume(), x, t});
            }
          }
        }
        std::stable_sort(trims.begin(), trims.end(), [](const Trim& a, const Trim& b) { return a.removed < b.removed; });
        for (const Trim& t : trims)
          if (state.try_replace(t.box, t.result)) {
            ++num_shrunk;
            changed = true;
            break;
          }
      }
    if (!changed) break;
  }
  return num_shrunk;
}

}  // namespace

SnapShrinkResult snap_and_shrink(const SolidIndex& index, std::vector<HeightBox> boxes,
                                 const SnapShrinkOptions& options) {
  if (options.max_shrink_passes < 0)
    throw InvalidArgumentError("snap_and_shrink: max_shrink_passes must be >= 0");
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const Box3& b = boxes[i].box;
    if (!b.min.allFinite() || !b.max.allFinite() || (b.min.array() > b.max.array()).any())
      throw InvalidArgumentError("snap_and_shrink: box " + std::to_string(i) + " has non-finite or inverted corners");
    if (!index.box_is_valid(boxes[i]))
      throw InvalidArgumentError("snap_and_shrink: box " + std::to_string(i) + " (axis " +
                                 std::string(axis_name(boxes[i].axis)) + ") is not a valid height box");
  }
  const double snap = options.snap_distance < 0 ? average_edge_length(index.mesh()) : options.snap_distance;
  CoverState state(index, std::move(boxes), options.max_height, options.machine_size);
  SnapShrinkResult result;
  if (snap > 0) result.num_snapped = snap_faces(state, snap);
  if (options.shrink) result.num_shrunk = shrink_overlaps(state, options.max_shrink_passes);
  result.boxes = state.release();
  if (options.progress)
    options.progress->info("snap and shrink: " + std::to_string(result.num_snapped) + " faces snapped, " +
                           std::to_string(result.num_shrunk) + " overlaps trimmed");
  return result;
}

}  // namespace subfab::detail

namespace subfab {

SnapShrinkResult snap_and_shrink(const Mesh& mesh, std::vector<HeightBox> boxes, const SnapShrinkOptions& options) {
  const detail::SolidIndex index(mesh, overhang_sine(options.max_overhang_deg), options.allowed_overhangs,
                                 options.overhang_floors);
  return detail::snap_and_shrink(index, std::move(boxes), options);
}

}  // namespace subfab
