// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/remove_slivers.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "decompose/block_pairs_detail.h"
#include "geometry/clip_solid_to_box.h"
#include "geometry/deterministic_arena.h"
#include "geometry/exact_mesh.h"
#include "geometry/solid_index.h"
#include "geometry/surface_deviation.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/merge_within_tolerance.h"
#include "subfab/validate/find_slivers.h"
#include "subfab/validate/milled_shape.h"
#include "subfab/validate/validate_decomposition.h"

namespace subfab {
namespace {


BoundingBox widened(BoundingBox box, double margin) {
  box.min.array() -= margin;
  box.max.array() += margin;
  return box;
}

//! The faces of `mesh` whose bounding box meets `box`.
std::vector<int> faces_meeting(const Mesh& mesh, const BoundingBox& box) {
  std::vector<int> out;
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    BoundingBox fb;
    for (int v : mesh.faces[f]) fb.extend(mesh.vertices[static_cast<std::size_t>(v)]);
    if (detail::boxes_touch(fb, box)) out.push_back(static_cast<int>(f));
  }
  return out;
}

//! The bound (measure + error) of the deviation that dropping sliver `b`
//! causes (see remove_slivers.h); `why` (when set and the bound exceeds T)
//! says how far the input near it lies from the other blocks.
double drop_bound(const Mesh& solid, const std::vector<Block>& blocks, const std::vector<BoundingBox>& boxes,
                  std::size_t b, double tolerance, double error, std::string* why = nullptr) {
  const BoundingBox near = widened(boxes[b], 2.0 * tolerance);
  detail::DistanceMesh others;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    if (k == b || !detail::boxes_touch(boxes[k], near)) continue;
    detail::append_distance_patch(others, blocks[k].mesh, nullptr);  // milled shapes too: they cover what they fill
  }
  const BoundingBox reach = widened(boxes[b], tolerance);
  const Mesh near_input = detail::clipped_faces(solid, faces_meeting(solid, reach), reach);
  detail::DistanceMesh input_near;
  detail::append_distance_patch(input_near, near_input, nullptr);
  // The input surface near the sliver stays within T of another block.
  const double covered = detail::one_sided_hausdorff(input_near, others, error);
  if (why && !(covered + error <= tolerance))
    *why = "the input near it lies " + std::to_string(covered / tolerance) + " T from the other blocks";
  return covered + error;
}

//! Stages 1 (drops) and 2 (merges) of remove_slivers() on `r.blocks`, the
//! slivers among them restricted to the blocks flagged in `only` (all when
//! nullptr); counts and the deviation bound added to `r`.
void drop_and_merge(const Mesh& solid, SliverRemovalResult& r, const SliverRemovalOptions& options,
                    const std::vector<char>* only) {
  const double error = options.error_fraction * options.tolerance;
  const auto flagged = [&] {
    std::vector<char> flags = sliver_flags(solid, r.blocks, options.min_thickness);
    if (only)
      for (std::size_t i = 0; i < flags.size(); ++i) flags[i] = static_cast<char>(flags[i] && (*only)[i]);
    return flags;
  };
  std::vector<char> keep_only = only ? *only : std::vector<char>{};
  // 1. Drops of the slivers the model does without, measured within the
  //    tolerance (cheap: two bounded-error distances each). A drop changes
  //    what covers its neighbourhood: per pass, only slivers farther than 2T
  //    from every block dropped in it (in block order).
  for (int pass = 0; pass < 4; ++pass) {
    const std::vector<char> flags = flagged();
    std::vector<std::size_t> slivers;
    for (std::size_t i = 0; i < flags.size(); ++i)
      if (flags[i]) slivers.push_back(i);
    if (slivers.empty()) break;
    const std::vector<BoundingBox> boxes = detail::block_boxes(r.blocks);
    std::vector<double> bound(slivers.size());
    parallel_for(0, slivers.size(), [&](std::size_t s) {
      bound[s] = drop_bound(solid, r.blocks, boxes, slivers[s], options.tolerance, error);
    });
    std::vector<char> drop(r.blocks.size(), 0);
    std::vector<BoundingBox> dropped;
    for (std::size_t s = 0; s < slivers.size(); ++s) {
      if (!(bound[s] <= options.tolerance)) continue;
      const BoundingBox reach = widened(boxes[slivers[s]], 2.0 * options.tolerance);
      if (std::any_of(dropped.begin(), dropped.end(), [&](const BoundingBox& d) { return detail::boxes_touch(d, reach); }))
        continue;  // measured again next pass
      dropped.push_back(reach);
      drop[slivers[s]] = 1;
      r.max_deviation = std::max(r.max_deviation, bound[s]);
    }
    if (dropped.empty()) break;
    r.num_dropped += dropped.size();
    std::vector<Block> kept;
    std::vector<char> kept_filled, kept_only;
    for (std::size_t i = 0; i < r.blocks.size(); ++i)
      if (!drop[i]) {
        kept.push_back(std::move(r.blocks[i]));
        if (!r.filled.empty()) kept_filled.push_back(r.filled[i]);
        if (only) kept_only.push_back(keep_only[i]);
      }
    r.blocks = std::move(kept);
    r.filled = std::move(kept_filled);
    keep_only = std::move(kept_only);
    if (only) only = &keep_only;
  }
  // 2. Merges of each sliver left with a neighbour, within the tolerance.
  const std::vector<char> flags = flagged();
  if (std::count(flags.begin(), flags.end(), char{1}) == 0) return;
  ToleranceMergeOptions to;
  to.tolerance = options.tolerance;
  to.error_fraction = options.error_fraction;
  to.max_height = options.max_height;
  to.machine_size = options.machine_size;
  to.screen_factor = options.screen_factor;
  to.max_pair_faces = options.max_pair_faces;
  to.max_region_faces = options.max_region_faces;
  if (!r.filled.empty()) to.filled = &r.filled;
  to.focus = &flags;
  to.clean_rounding = true;
  to.block_defect = options.block_defect;
  to.progress = options.progress;
  ToleranceMergeResult merged = merge_within_tolerance(solid, std::move(r.blocks), to);
  r.num_merged += merged.num_merges;
  r.max_deviation = std::max(r.max_deviation, merged.max_deviation);
  r.blocks = std::move(merged.blocks);
  r.filled = std::move(merged.filled);
}

//! The planes a sliver is split across (split_slivers()): (k, c) for each
//! coordinate c strictly inside the box of `mesh` along axis k where faces
//! of `mesh` lie in the plane x_k = c; the planes with the most face area
//! first (ties by axis, then c ascending), at most `limit`.
std::vector<std::pair<int, double>> split_planes(const Mesh& mesh, std::size_t limit) {
  const BoundingBox box = bounding_box(mesh);
  std::map<std::pair<int, double>, double> area;
  for (const Triangle& t : mesh.faces) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    for (int k = 0; k < 3; ++k)
      if (a[k] == b[k] && b[k] == c[k] && a[k] > box.min[k] && a[k] < box.max[k])
        area[{k, a[k]}] += 0.5 * (b - a).cross(c - a).norm();
  }
  std::vector<std::pair<double, std::pair<int, double>>> order;
  for (const auto& [plane, w] : area) order.emplace_back(-w, plane);
  std::stable_sort(order.begin(), order.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::pair<int, double>> out;
  for (std::size_t i = 0; i < order.size() && i < limit; ++i) out.push_back(order[i].second);
  return out;
}

//! `block` cut across the plane x_k = c into its pieces (exact clip to the
//! two half-boxes, each rounded to doubles), when there are at least two
//! and each is an exact height field along the block's axis that rounds
//! without degenerate or flipped faces; else nullopt.
std::optional<std::vector<Block>> split_block(const Block& block, int k, double c) {
  const BoundingBox box = bounding_box(block.mesh);
  const double margin = std::max(1.0, box.diagonal());
  std::optional<std::vector<Block>> out;
  detail::warm_up_exact_booleans();
  const detail::SolidIndex index(block.mesh);
  std::vector<Mesh> meshes;
  bool ok = true;
  const std::string error = detail::run_in_arena([&] {
    for (int side = 0; side < 2 && ok; ++side) {
      Box3 half{(box.min.array() - margin).matrix(), (box.max.array() + margin).matrix()};
      (side == 0 ? half.max[k] : half.min[k]) = c;
      std::vector<detail::ExactMesh> pieces = detail::clip_solid_to_box(block.mesh, index, half);
      detail::SuspendArena heap;
      for (const detail::ExactMesh& piece : pieces) {
        detail::RoundingReport rounding;
        Mesh m = detail::to_double(piece, &rounding);
        if (rounding.num_degenerate_faces + rounding.num_flipped_faces > 0 || m.faces.empty()) {
          ok = false;
          break;
        }
        meshes.push_back(std::move(m));
      }
    }
  });
  if (!error.empty() || !ok || meshes.size() < 2) return out;
  const Vec3 d = axis_direction(block.axis);
  std::vector<Block> blocks;
  for (Mesh& m : meshes) {
    if (!check_closed_solid(m).ok() || detail::count_degenerate_faces(m) > 0) return out;
    try {
      if (!milled_shape(m, d).is_block) return out;
    } catch (const std::exception&) {
      return out;
    }
    blocks.push_back(Block{std::move(m), block.axis, block.source_box});
  }
  out = std::move(blocks);
  return out;
}

//! Stage 3 of remove_slivers(): each sliver left (in block order) is split
//! across the planes of split_planes() in turn; the first split after which
//! stages 1 and 2, run on its pieces, leave none of them a sliver (and no
//! more slivers in all) is kept. The pieces are exact (the clip is exact,
//! each piece checked as a block after rounding); what the drops and merges
//! of the pieces change is measured as in stages 1 and 2.
void split_slivers(const Mesh& solid, SliverRemovalResult& r, const SliverRemovalOptions& options) {
  std::vector<char> flags = sliver_flags(solid, r.blocks, options.min_thickness);
  std::size_t left = static_cast<std::size_t>(std::count(flags.begin(), flags.end(), char{1}));
  std::set<std::vector<double>> hopeless;  // slivers every split failed on, by box and face count
  const auto key = [](const Mesh& m) {
    const BoundingBox b = bounding_box(m);
    return std::vector<double>{b.min.x(), b.min.y(), b.min.z(), b.max.x(), b.max.y(), b.max.z(),
                               static_cast<double>(m.num_faces())};
  };
  while (left > 0) {
    std::size_t s = r.blocks.size();
    for (std::size_t i = 0; i < flags.size() && s == r.blocks.size(); ++i)
      if (flags[i] && !hopeless.count(key(r.blocks[i].mesh))) s = i;
    if (s == r.blocks.size()) break;
    bool split = false;
    for (const auto& [k, c] : split_planes(r.blocks[s].mesh, options.max_split_planes)) {
      std::optional<std::vector<Block>> pieces = split_block(r.blocks[s], k, c);
      if (!pieces) continue;
      SliverRemovalResult trial;
      std::vector<char> only;
      for (std::size_t i = 0; i < r.blocks.size(); ++i) {
        if (i == s) {
          for (Block& p : *pieces) {
            trial.blocks.push_back(std::move(p));
            if (!r.filled.empty()) trial.filled.push_back(r.filled[i]);
            only.push_back(1);
          }
          continue;
        }
        trial.blocks.push_back(r.blocks[i]);
        if (!r.filled.empty()) trial.filled.push_back(r.filled[i]);
        only.push_back(0);
      }
      drop_and_merge(solid, trial, options, &only);
      const std::vector<char> after = sliver_flags(solid, trial.blocks, options.min_thickness);
      const std::size_t now = static_cast<std::size_t>(std::count(after.begin(), after.end(), char{1}));
      if (now >= left) continue;
      r.blocks = std::move(trial.blocks);
      r.filled = std::move(trial.filled);
      r.num_merged += trial.num_merged;
      r.num_dropped += trial.num_dropped;
      r.max_deviation = std::max(r.max_deviation, trial.max_deviation);
      ++r.num_split;
      flags = after;
      left = now;
      split = true;
      break;
    }
    if (!split) hopeless.insert(key(r.blocks[s].mesh));
  }
}

}  // namespace

std::vector<char> sliver_flags(const Mesh& solid, const std::vector<Block>& blocks, double min_thickness) {
  std::vector<SliverBlock> sb(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) sb[i].mesh = &blocks[i].mesh;  // identity frame: canonical axes
  std::vector<char> flags(blocks.size(), 0);
  if (blocks.empty()) return flags;
  const std::vector<SliverMeasure> m = find_slivers(solid, sb, {.min_thickness = min_thickness});
  for (std::size_t i = 0; i < m.size(); ++i) flags[i] = m[i].sliver ? 1 : 0;
  return flags;
}

SliverRemovalResult remove_slivers(const Mesh& solid, std::vector<Block> blocks, const SliverRemovalOptions& options) {
  if (!(options.min_thickness > 0) || !std::isfinite(options.min_thickness))
    throw InvalidArgumentError("remove_slivers: min_thickness must be a positive length (model units)");
  if (!(options.tolerance >= 0) || !std::isfinite(options.tolerance))
    throw InvalidArgumentError("remove_slivers: the tolerance must be a length >= 0");
  if (!(options.error_fraction > 0 && options.error_fraction < 1))
    throw InvalidArgumentError("remove_slivers: the error fraction must lie in (0, 1)");
  if (options.filled && options.filled->size() != blocks.size())
    throw InvalidArgumentError("remove_slivers: one filled flag per block expected");
  StageScope stage(options.progress, "slivers");
  SliverRemovalResult result;
  if (options.filled) result.filled = *options.filled;
  std::vector<char> flags = sliver_flags(solid, blocks, options.min_thickness);
  result.num_found = static_cast<std::size_t>(std::count(flags.begin(), flags.end(), char{1}));
  result.num_left = result.num_found;
  if (result.num_found == 0 || options.tolerance == 0) {
    if (options.progress && result.num_found > 0)
      options.progress->warn(std::to_string(result.num_found) + " sliver block(s) thinner than " +
                             std::to_string(options.min_thickness) +
                             " model units where the model is thicker (exact decomposition: nothing may deviate, "
                             "they are kept; validate check 9 lists them)");
    result.blocks = std::move(blocks);
    return result;
  }
  result.blocks = std::move(blocks);
  const double error = options.error_fraction * options.tolerance;
  // 1. and 2.: drops, then merges, of every sliver.
  drop_and_merge(solid, result, options, nullptr);
  // 3. Splits of each sliver left across a plane of its own faces, when
  //    the drops and merges then remove every thin piece.
  split_slivers(solid, result, options);
  flags = sliver_flags(solid, result.blocks, options.min_thickness);
  result.num_left = static_cast<std::size_t>(std::count(flags.begin(), flags.end(), char{1}));
  if (options.progress) {
    options.progress->info(std::to_string(result.num_found) + " sliver block(s) thinner than " +
                           std::to_string(options.min_thickness) + " model units: " +
                           std::to_string(result.num_merged) + " merged into a neighbour and " +
                           std::to_string(result.num_dropped) + " dropped within the tolerance (" +
                           std::to_string(result.num_split) + " split first), " +
                           std::to_string(result.num_left) + " left");
    if (result.num_left > 0) {
      // Why each sliver left could not be dropped (the merges tried every neighbour, the splits every plane).
      const std::vector<BoundingBox> boxes = detail::block_boxes(result.blocks);
      for (std::size_t i = 0, shown = 0; i < flags.size() && shown < 8; ++i) {
        if (!flags[i]) continue;
        ++shown;
        std::string why = "measured within T";
        drop_bound(solid, result.blocks, boxes, i, options.tolerance, error, &why);
        const Vec3 size = boxes[i].max - boxes[i].min;
        options.progress->info("sliver left: block " + std::to_string(i + 1) + " (" +
                               std::to_string(result.blocks[i].mesh.num_faces()) + " faces, box " +
                               std::to_string(size.x()) + " x " + std::to_string(size.y()) + " x " +
                               std::to_string(size.z()) + " at " + std::to_string(boxes[i].min.x()) + ", " +
                               std::to_string(boxes[i].min.y()) + ", " + std::to_string(boxes[i].min.z()) +
                               "): no drop: " + why + "; no merge with a neighbour within T; no split of it whose thin pieces go");
      }
    }
    if (result.num_left > 0)
      options.progress->warn(std::to_string(result.num_left) +
                             " sliver block(s) no drop, merge or split keeps within the tolerance are kept "
                             "(validate check 9 lists them)");
  }
  return result;
}

}  // namespace subfab

