// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/merge_within_tolerance.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include "decompose/block_pairs_detail.h"
#include "geometry/undercut_depth.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/finalize_blocks.h"
#include "subfab/validate/fill_deviation_upper_bound.h"
#include "subfab/validate/measure_fill_deviation.h"
#include "subfab/validate/milled_shape.h"
#include "subfab/validate/validate_decomposition.h"
#include "validate/validate_booleans.h"

namespace subfab {
namespace {


BoundingBox widened(BoundingBox box, double margin) {
  box.min.array() -= margin;
  box.max.array() += margin;
  return box;
}

//! The union of two touching blocks when it is one closed 2-manifold piece
//! that rounds to doubles without degenerate or flipped faces (exact
//! corefinement in a deterministic arena). With `clean` (remove_slivers()),
//! a union whose rounding leaves such faces (thin triangles where the
//! corefinement cut the glued faces) gets export's cleanup instead
//! (clean_rounded_block(), relative tolerance 1e-10 of the scale, along
//! `direction`) and is kept when it is then a closed 2-manifold without
//! zero-area faces; `*moved` is set to the cleanup's tolerance (how far a
//! vertex may have moved, model units), else 0.
std::optional<Mesh> exact_union(const Mesh& a, const Mesh& b, bool clean, const Vec3& direction, double* moved) {
  detail::RoundingReport rounding;
  std::optional<Mesh> u = detail::exact_block_union(a, b, nullptr, rounding);
  *moved = 0.0;
  if (!u || rounding.num_degenerate_faces + rounding.num_flipped_faces == 0) return u;
  if (!clean) return std::nullopt;
  const std::optional<double> tolerance = clean_to_closed_solid(*u, direction);
  if (!tolerance) return std::nullopt;
  *moved = *tolerance;
  return u;
}

//! Quick screen of a direction for the union `u` (a heuristic: it only
//! skips directions, the exact tests decide): the thickness of the material
//! a machine would leave under each face of u that leans past vertical
//! (UndercutDepth: the free length along -d below the face, to u or the
//! base, times the face's unit n.d) must stay within `limit`. Thick fills
//! put the input surface they cover far from any surface of the result.
class FillScreen {
 public:
  explicit FillScreen(const Mesh& u) : depth_(u) {}

  bool passes(const Vec3& d, double limit) const {
    const Mesh& mesh = depth_.mesh();
    double base = std::numeric_limits<double>::infinity();
    for (const Vec3& v : mesh.vertices) base = std::min(base, v.dot(d));
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
      double top = -std::numeric_limits<double>::infinity();
      for (int v : mesh.faces[f]) top = std::max(top, mesh.vertices[static_cast<std::size_t>(v)].dot(d));
      if (depth_.depth(f, d, top - base, limit) > limit) return false;
    }
    return true;
  }

 private:
  detail::UndercutDepth depth_;
};

//! An accepted merge.
struct Candidate {
  Mesh mesh;
  Axis axis = Axis::PosZ;
  bool filled = false;  // the new block sticks out of the solid
  double bound = 0.0;   // deviation bound measured near it (0 when nothing new sticks out)
};

//! Why a pair was not merged: one bit per test that rejected one of its
//! directions (reported per round, to show what limits the merges).
enum Rejection : unsigned {
  kLimits = 1u << 0,     // no direction within the limits and the fill screen
  kUnion = 1u << 1,      // the exact union failed or is not one solid
  kMilled = 1u << 2,     // the milled shape failed or is not a closed height field
  kDeviation = 1u << 3,  // the model would leave the tolerance
  kCollision = 1u << 4,  // the milled shape overlaps another block
  kDefect = 1u << 5,     // export's check of the merged block failed
};

//! "limits 3, deviation 12, ...": how many rejected pairs each test rejected.
std::string rejection_summary(const std::vector<unsigned>& why) {
  static const std::pair<unsigned, const char*> names[] = {{kLimits, "limits/screen"}, {kUnion, "union"},
                                                          {kMilled, "milled shape"},   {kDeviation, "deviation"},
                                                          {kCollision, "collision"},   {kDefect, "export check"}};
  std::string out;
  for (const auto& [bit, name] : names) {
    const auto n = std::count_if(why.begin(), why.end(), [bit](unsigned w) { return (w & bit) != 0; });
    if (n == 0) continue;
    out += (out.empty() ? "" : ", ") + std::string(name) + " " + std::to_string(n);
  }
  return out;
}

//! Each block's detail::inside_test_index(), built on first use (once,
//! from whichever evaluation asks first).
class LazyIndexes {
 public:
  explicit LazyIndexes(const std::vector<Block>& blocks)
      : blocks_(blocks), once_(std::make_unique<std::once_flag[]>(blocks.size())), index_(blocks.size()) {}
  const detail::SolidIndex* operator()(std::size_t k) const {
    std::call_once(once_[k], [&] { index_[k] = detail::inside_test_index(blocks_[k].mesh); });
    return index_[k].get();
  }

 private:
  const std::vector<Block>& blocks_;
  std::unique_ptr<std::once_flag[]> once_;
  mutable std::vector<std::unique_ptr<detail::SolidIndex>> index_;
};

//! The state the evaluation of a pair reads.
struct State {
  const std::vector<Block>& blocks;
  const std::vector<char>& filled;
  const std::vector<BoundingBox>& boxes;
  const std::vector<double>& volumes;
  const LazyIndexes& indexes;
};

std::optional<Candidate> evaluate(std::size_t i, std::size_t j, const State& s, const FillDeviationMeter& meter,
                                  const ToleranceMergeOptions& o, std::size_t& tried, unsigned& why) {
  // Cheap tests first, on the two blocks (the union's box is their boxes'
  // union; the screen casts against both blocks' faces, glued ones included).
  BoundingBox ubox = s.boxes[i];
  ubox.extend(s.boxes[j].min);
  ubox.extend(s.boxes[j].max);
  std::vector<Axis> order{s.blocks[i].axis};
  if (s.blocks[j].axis != s.blocks[i].axis)
    order.insert(s.volumes[j] > s.volumes[i] ? order.begin() : order.end(), s.blocks[j].axis);
  for (Axis x : kAllAxes)
    if (std::find(order.begin(), order.end(), x) == order.end()) order.push_back(x);
  Mesh both = s.blocks[i].mesh;
  {
    const int offset = static_cast<int>(both.num_vertices());
    both.vertices.insert(both.vertices.end(), s.blocks[j].mesh.vertices.begin(), s.blocks[j].mesh.vertices.end());
    for (Triangle t : s.blocks[j].mesh.faces) {
      for (int& v : t) v += offset;
      both.faces.push_back(t);
    }
  }
  const FillScreen screen(both);
  std::vector<Axis> axes;
  for (Axis axis : order)
    if (detail::within_limits(ubox, axis, o.max_height, o.machine_size) && screen.passes(axis_direction(axis), o.screen_factor * o.tolerance))
      axes.push_back(axis);
  if (axes.empty()) {
    why |= kLimits;
    return std::nullopt;
  }
  double moved = 0.0;
  const std::optional<Mesh> u =
      exact_union(s.blocks[i].mesh, s.blocks[j].mesh, o.clean_rounding, axis_direction(axes.front()), &moved);
  if (!u) {
    why |= kUnion;
    return std::nullopt;
  }
  std::vector<const Mesh*> others;
  for (std::size_t k = 0; k < s.blocks.size(); ++k)
    if (k != i && k != j && s.filled[k]) others.push_back(&s.blocks[k].mesh);
  const double error = o.error_fraction * o.tolerance;
  for (Axis axis : axes) {
    const Vec3 d = axis_direction(axis);
    MilledShape milled;
    try {
      milled = milled_shape(*u, d);
    } catch (const std::exception&) {
      why |= kMilled;
      continue;
    }
    ++tried;
    if (milled.is_block) {
      // A cleaned union is kept only when it is a valid block as export checks it
      // (closed, oriented, no zero-area face, no self-intersection, height field).
      if ((moved > 0 && !block_defect(*u, d, bounding_box(*u).diagonal()).empty()) ||
          (o.block_defect && !o.block_defect(Block{*u, axis, -1}).empty())) {
        why |= kDefect;
        continue;
      }
      return Candidate{*u, axis, s.filled[i] || s.filled[j], 0.0};
    }
    const Mesh& m = milled.mesh;
    if (!check_closed_solid(m).ok() || !is_height_field(m, d)) {
      why |= kMilled;
      continue;
    }
    // What m adds to the union (which overlaps no block): its fill, in
    // these boxes (measure_fill_deviation.h; nullopt: not bounded). Where
    // neither block sticks out, the union lies in the solid and m's part
    // outside it lies in the fill too.
    const std::optional<std::vector<BoundingBox>> columns = fill_face_columns(*u, m, axis);
    std::optional<std::vector<BoundingBox>> tiles;
    if (columns) tiles = tile_columns(*columns, m, axis);
    const bool inside = !s.filled[i] && !s.filled[j];
    // The deviation first (it rejects most), then collisions (exact booleans).
    // Where neither block sticks out, the union lies in the solid and only
    // its fill can deviate (measure_fill(), local); else near the whole union.
    // First the bound over the union's part outside the solid
    // (fill_deviation_upper_bound.h: one exact difference, then distances
    // over its faces); the exact measure only where it does not keep the
    // union within the tolerance.
    double bound = std::numeric_limits<double>::infinity();
    try {
      std::optional<BoundingBox> within;
      if (inside && tiles && !tiles->empty()) within = detail::fill_hull(*tiles, bounding_box(m));
      const detail::OutsidePart part = detail::outside_part(m, meter.solid(), within ? &*within : nullptr);
      if (part.faces()) {
        std::vector<const Mesh*> all{&m};
        all.insert(all.end(), others.begin(), others.end());
        std::vector<FillPart> view(all.size());
        view[0] = {part.faces(), &part.on_input};
        std::vector<char> which(all.size(), 0);
        which[0] = 1;
        bound = fill_deviation_upper_bounds(meter.solid(), all, view, {.error = error, .stop = o.tolerance}, which)
                    .blocks[0]
                    .bound();
      }
    } catch (const std::exception&) {
      // no bound: measured below
    }
    if (!(bound + moved <= o.tolerance)) {
      const FillDeviationOptions fo{.reach = o.tolerance, .error = error, .max_faces = o.max_region_faces};
      const FillDeviation dev =
          inside && tiles ? meter.measure_fill(m, others, *tiles, fo) : meter.measure(m, others, fo);
      if (!dev.failure.empty() || dev.bound() + moved > o.tolerance) {
        why |= kDeviation;
        continue;
      }
      bound = dev.bound();
    }
    const detail::AddedFill added{tiles ? &*tiles : nullptr, columns ? &*columns : nullptr,
                                  [&](std::size_t k) { return s.indexes(k); }};
    if (detail::overlaps_a_block(m, s.blocks, s.boxes, s.volumes, [&](std::size_t k) { return k == i || k == j; },
                                 o.collision_tolerance, tiles ? &added : nullptr)) {
      why |= kCollision;
      continue;
    }
    if (o.block_defect && !o.block_defect(Block{m, axis, -1}).empty()) {
      why |= kDefect;
      continue;
    }
    return Candidate{m, axis, true, bound + moved};
  }
  return std::nullopt;
}

}  // namespace

ToleranceMergeResult merge_within_tolerance(const Mesh& solid, std::vector<Block> blocks,
                                            const ToleranceMergeOptions& options) {
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
    throw InvalidArgumentError("merge_within_tolerance: the tolerance must be a positive length");
  if (!(options.error_fraction > 0 && options.error_fraction < 1))
    throw InvalidArgumentError("merge_within_tolerance: the error fraction must lie in (0, 1)");
  ToleranceMergeResult result;
  const FillDeviationMeter meter(solid);
  if (options.filled && options.filled->size() != blocks.size())
    throw InvalidArgumentError("merge_within_tolerance: one filled flag per block expected");
  std::vector<char> filled = options.filled ? *options.filled : std::vector<char>(blocks.size(), 0);
  if (options.focus && options.focus->size() != blocks.size())
    throw InvalidArgumentError("merge_within_tolerance: one focus flag per block expected");
  std::vector<char> focus = options.focus ? *options.focus : std::vector<char>(blocks.size(), 1);
  std::vector<std::size_t> ids(blocks.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = i;
  std::size_t next_id = blocks.size();
  std::map<std::pair<std::size_t, std::size_t>, bool> rejected;
  StageScope stage(options.progress, "tolerance merge");
  for (int round = 0; round < options.max_rounds; ++round) {
    const std::vector<BoundingBox> boxes = detail::block_boxes(blocks);
    const std::vector<double> volumes = detail::block_volumes(blocks);
    // pairs, smallest smaller block first
    std::vector<std::tuple<double, std::size_t, std::size_t>> order;
    std::size_t too_large = 0;  // touching pairs over max_pair_faces
    for (std::size_t i = 0; i < blocks.size(); ++i)
      for (std::size_t j = i + 1; j < blocks.size(); ++j)
        if ((focus[i] || focus[j]) && detail::boxes_touch(boxes[i], boxes[j]) && !rejected.count({ids[i], ids[j]})) {
          if (blocks[i].mesh.num_faces() + blocks[j].mesh.num_faces() <= options.max_pair_faces)
            order.emplace_back(std::min(volumes[i], volumes[j]), i, j);
          else
            ++too_large;
        }
    if (order.empty()) break;
    std::sort(order.begin(), order.end());
    const LazyIndexes indexes(blocks);
    const State state{blocks, filled, boxes, volumes, indexes};
    std::vector<std::optional<Candidate>> found(order.size());
    std::vector<std::size_t> tried(order.size(), 0);
    std::vector<unsigned> why(order.size(), 0);
    std::atomic<std::size_t> done{0};
    parallel_for(0, order.size(), [&](std::size_t p) {
      const auto [v, i, j] = order[p];
      found[p] = evaluate(i, j, state, meter, options, tried[p], why[p]);
      if (options.progress) options.progress->update(++done, order.size());
    });
    for (std::size_t t : tried) result.num_candidates += t;
    std::vector<char> used(blocks.size(), 0), removed(blocks.size(), 0);
    std::vector<BoundingBox> changed;
    const double margin = 3.0 * options.tolerance;
    std::size_t merged_now = 0;
    std::vector<unsigned> rejected_now;
    for (std::size_t p = 0; p < order.size(); ++p) {
      const auto [v, i, j] = order[p];
      if (!found[p]) {
        rejected[{ids[i], ids[j]}] = true;
        rejected_now.push_back(why[p]);
        continue;
      }
      if (used[i] || used[j]) continue;  // evaluated again next round
      const BoundingBox reach = widened(bounding_box(found[p]->mesh), margin);
      if (std::any_of(changed.begin(), changed.end(), [&](const BoundingBox& c) { return detail::boxes_touch(c, reach); }))
        continue;  // near a block changed this round: evaluated again next round
      used[i] = used[j] = 1;
      changed.push_back(reach);
      result.max_deviation = std::max(result.max_deviation, found[p]->bound);
      blocks[i].mesh = std::move(found[p]->mesh);
      blocks[i].axis = found[p]->axis;
      filled[i] = found[p]->filled ? 1 : 0;
      focus[i] = options.focus ? 0 : 1;
      ids[i] = next_id++;
      removed[j] = 1;
      ++merged_now;
    }
    if (options.progress)
      options.progress->info("tolerance merge round " + std::to_string(round + 1) + ": " + std::to_string(order.size()) +
                             " pairs, " + std::to_string(merged_now) + " merged" +
                             (rejected_now.empty() ? std::string()
                                                   : "; rejected " + std::to_string(rejected_now.size()) + " (" +
                                                         rejection_summary(rejected_now) + ")") +
                             (too_large ? "; " + std::to_string(too_large) + " pairs over the face cap" : ""));
    if (merged_now == 0) break;
    result.num_merges += merged_now;
    std::vector<Block> kept;
    std::vector<std::size_t> kept_ids;
    std::vector<char> kept_filled, kept_focus;
    for (std::size_t i = 0; i < blocks.size(); ++i)
      if (!removed[i]) {
        kept.push_back(std::move(blocks[i]));
        kept_ids.push_back(ids[i]);
        kept_filled.push_back(filled[i]);
        kept_focus.push_back(focus[i]);
      }
    blocks = std::move(kept);
    ids = std::move(kept_ids);
    filled = std::move(kept_filled);
    focus = std::move(kept_focus);
  }
  result.blocks = std::move(blocks);
  result.filled = std::move(filled);
  return result;
}

}  // namespace subfab
