// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/remove_slivers.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "decompose/block_pairs_detail.h"
#include "geometry/clip_solid_to_box.h"
#include "validate/validate_booleans.h"
#include "geometry/deterministic_arena.h"
#include "geometry/exact_mesh.h"
#include "geometry/solid_index.h"
#include "geometry/surface_deviation.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/finalize_blocks.h"
#include "subfab/decompose/merge_within_tolerance.h"
#include "subfab/validate/block_thickness.h"
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
  // CGAL's corefinement may crash (not throw) on a mesh that intersects
  // itself or has zero-area faces: such a block is not split (egea at
  // 8.3e-2, session 35: a merged sliver, SIGSEGV in the clip).
  if (!detail::boolean_input_defect(block.mesh, true).empty()) return out;
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

//! A sliver's thickening (remove_slivers.h, 4.): the blocks that replace
//! the sliver and the neighbours it took material from.
struct Thickening {
  std::vector<std::size_t> replaced;  // the sliver first, then the neighbours
  std::vector<Block> blocks;          // the thickened sliver first, then the neighbours' pieces
  std::vector<char> filled;           // per new block (when the caller tracks them)
  std::vector<std::size_t> pieces;    // per replaced block: how many of `blocks` are its (1 for the sliver)
  double moved = 0.0;                 // how far export's cleanup of a rounded piece may have moved a vertex
};

//! Does `mesh` have a face in the plane x_k = c (exactly)?
bool has_face_in_plane(const Mesh& mesh, int k, double c) {
  for (const Triangle& t : mesh.faces)
    if (mesh.vertices[static_cast<std::size_t>(t[0])][k] == c && mesh.vertices[static_cast<std::size_t>(t[1])][k] == c &&
        mesh.vertices[static_cast<std::size_t>(t[2])][k] == c)
      return true;
  return false;
}

//! `mesh` (no two vertices at one exact point) rounded to doubles; when
//! that leaves degenerate or flipped faces (thin triangles where the
//! corefinement cut a face near a region's plane), export's cleanup along
//! `direction` (clean_rounded_block(), 1e-10 x the scale; `*moved` raised to
//! that tolerance). Nullopt unless the result is a closed solid without
//! zero-area faces. Runs on the heap (callable inside an arena).
std::optional<Mesh> rounded_solid(const detail::ExactMesh& mesh, const Vec3& direction, double* moved) {
  if (mesh.number_of_faces() == 0 || detail::has_coincident_vertices(mesh)) return std::nullopt;
  detail::SuspendArena heap;
  detail::RoundingReport rounding;
  Mesh m = detail::to_double(mesh, &rounding);
  if (rounding.num_degenerate_faces + rounding.num_flipped_faces > 0) {
    const std::optional<double> tolerance = clean_to_closed_solid(m, direction);
    if (!tolerance) return std::nullopt;
    *moved = std::max(*moved, *tolerance);
  }
  return m;
}

//! The axis `mesh` is an exact height field along within the limits,
//! `preferred` first, then the others in kAllAxes order; nullopt when none.
std::optional<Axis> block_axis(const Mesh& mesh, Axis preferred, const SliverRemovalOptions& options) {
  if (!check_closed_solid(mesh).ok() || detail::count_degenerate_faces(mesh) > 0) return std::nullopt;
  const BoundingBox box = bounding_box(mesh);
  std::vector<Axis> order{preferred};
  for (Axis a : kAllAxes)
    if (a != preferred) order.push_back(a);
  for (Axis a : order) {
    if (!detail::within_limits(box, a, options.max_height, options.machine_size)) continue;
    try {
      if (milled_shape(mesh, axis_direction(a)).is_block) return a;
    } catch (const std::exception&) {
    }
  }
  return std::nullopt;
}

//! One thickening of sliver `s` (remove_slivers.h, 4.): the neighbours
//! `near` give the sliver their material inside `regions[j]` (one box per
//! neighbour), and, when `interior` (the index of `solid`) is set, the
//! model inside `slab` joins it too, exactly; the sliver keeps its axis when it can (else the
//! first axis it is a height field along), each neighbour's remaining
//! pieces keep theirs. Nullopt unless every new block is a clean exact
//! height field within the limits, there are no more of them than before,
//! none is a sliver and each passes the export's check; `why` then says
//! what failed first.
std::optional<Thickening> try_thickening(const Mesh& solid, const std::vector<Block>& blocks,
                                         const std::vector<char>& filled, std::size_t s,
                                         const std::vector<std::size_t>& near, const std::vector<Box3>& regions,
                                         const detail::SolidIndex* interior, const Box3& slab,
                                         const SliverRemovalOptions& options, std::string& why) {
  const auto fail = [&](const char* what) {
    why = what;
    return std::nullopt;
  };
  namespace PMP = CGAL::Polygon_mesh_processing;
  if (blocks[s].mesh.num_faces() > options.max_thicken_faces) return fail("a sliver with too many faces");
  // CGAL's corefinement must not be given a face whose corners are
  // collinear (exact_mesh.h): it may never return (rotor's fallback). A
  // block with such faces (the export cleans them later) is used cleaned as
  // the export cleans it (clean_rounded_block(), 1e-10 x the scale).
  double moved = 0.0;
  // work[0]: the sliver's mesh, work[1 + j]: neighbour j's (cleaned copies where needed)
  std::vector<std::size_t> used{s};
  used.insert(used.end(), near.begin(), near.end());
  std::vector<Mesh> cleaned;
  cleaned.reserve(used.size());
  std::vector<const Mesh*> work;
  for (std::size_t b : used) {
    work.push_back(&blocks[b].mesh);
    if (detail::count_degenerate_faces(blocks[b].mesh) == 0) continue;
    cleaned.push_back(blocks[b].mesh);
    const std::optional<double> tolerance = clean_to_closed_solid(cleaned.back(), axis_direction(blocks[b].axis));
    if (!tolerance) return fail("a block with a zero-area face the cleanup does not remove");
    moved = std::max(moved, *tolerance);
    work.back() = &cleaned.back();
  }
  std::optional<Mesh> grown;
  std::vector<std::vector<Mesh>> rest(near.size());
  bool ok = true;
  detail::warm_up_exact_booleans();
  const char* reason = nullptr;  // not a std::string: nothing inside the arena may outlive it
  const std::string error = detail::run_in_arena([&] {
    // A mesh with two vertices at one point (a pinch CGAL's output splits)
    // is never given to the corefinement again: CGAL 5.5 can loop for ever
    // on one (decompose.h, the carve's pinch handling).
    const auto pinched = [&](const detail::ExactMesh& m) {
      if (!detail::has_coincident_vertices(m)) return false;
      reason = "a part that touches itself at a point";
      ok = false;
      return true;
    };
    detail::ExactMesh sliver = detail::to_exact(*work[0]);
    if (pinched(sliver)) return;
    // `piece` joins the sliver; false (and `ok` false) when that fails
    const auto join = [&](detail::ExactMesh& piece) {
      detail::ExactMesh u;
      if (pinched(piece)) return false;
      if (!PMP::corefine_and_compute_union(sliver, piece, u)) {
        reason = "a union that is no 2-manifold";
        ok = false;
        return false;
      }
      sliver = std::move(u);
      return !pinched(sliver);
    };
    if (interior)  // the model in the slab: what no block holds there joins the sliver
      for (detail::ExactMesh& piece : detail::clip_solid_to_box(solid, *interior, slab))
        if (!join(piece)) return;
    for (std::size_t j = 0; j < near.size() && ok; ++j) {
      detail::ExactMesh a = detail::to_exact(*work[1 + j]), b = detail::box_mesh(regions[j]), inside, outside;
      if (pinched(a)) return;
      detail::ExactMesh a2 = a, b2 = b;
      if (!PMP::corefine_and_compute_intersection(a, b, inside) ||
          !PMP::corefine_and_compute_difference(a2, b2, outside)) {
        reason = "a neighbour's part in or out of its region that is no 2-manifold";
        ok = false;
        return;
      }
      if (pinched(outside)) return;
      if (inside.number_of_faces() > options.max_thicken_faces) {
        reason = "a neighbour's part with too many faces";
        ok = false;
        return;
      }
      if (inside.number_of_faces() > 0 && !join(inside)) return;
      std::vector<detail::ExactMesh> pieces;
      if (outside.number_of_faces() > 0) PMP::split_connected_components(outside, pieces);
      for (const detail::ExactMesh& p : pieces) {
        std::optional<Mesh> m = rounded_solid(p, axis_direction(blocks[near[j]].axis), &moved);
        if (!m) {
          reason = "a neighbour's piece that does not round to a clean solid";
          ok = false;
          return;
        }
        detail::SuspendArena heap;
        rest[j].push_back(std::move(*m));
      }
    }
    if (!ok) return;
    auto fcc = sliver.add_property_map<detail::FaceIndex, std::size_t>("f:cc", 0).first;
    if (PMP::connected_components(sliver, fcc) != 1) {
      reason = "the sliver and what it takes are not one piece";
      ok = false;
      return;
    }
    std::optional<Mesh> m = rounded_solid(sliver, axis_direction(blocks[s].axis), &moved);
    detail::SuspendArena heap;
    grown = std::move(m);
  });
  if (!error.empty()) return fail("an exact boolean failed");
  if (!ok) return fail(reason ? reason : "an exact step failed");
  if (!grown) return fail("the thickened sliver does not round to a clean solid");
  std::size_t count = 1;
  for (const auto& r : rest) count += r.size();
  if (count > 1 + near.size()) return fail("a neighbour cut in two");
  Thickening t;
  t.moved = moved;
  t.replaced.push_back(s);
  t.replaced.insert(t.replaced.end(), near.begin(), near.end());
  t.pieces.push_back(1);
  for (const auto& r : rest) t.pieces.push_back(r.size());
  const std::optional<Axis> axis = block_axis(*grown, blocks[s].axis, options);
  if (!axis) return fail("the thickened sliver no exact height field within the limits");
  const bool track = !filled.empty();
  char any_filled = track ? filled[s] : 0;
  for (std::size_t j : near) any_filled = static_cast<char>(any_filled || (track && filled[j]));
  t.blocks.push_back(Block{std::move(*grown), *axis, blocks[s].source_box});
  if (track) t.filled.push_back(any_filled);  // it may hold what a neighbour's milled shape added
  for (std::size_t j = 0; j < near.size(); ++j)
    for (Mesh& m : rest[j]) {
      const Block& n = blocks[near[j]];
      if (!check_closed_solid(m).ok() || detail::count_degenerate_faces(m) > 0)
        return fail("a neighbour's piece that is no clean solid");
      try {
        if (!milled_shape(m, axis_direction(n.axis)).is_block)
          return fail("a neighbour's piece no exact height field along its axis");
      } catch (const std::exception&) {
        return fail("a neighbour's piece no exact height field along its axis");
      }
      t.blocks.push_back(Block{std::move(m), n.axis, n.source_box});
      if (track) t.filled.push_back(filled[near[j]]);
    }
  const std::vector<char> thin = sliver_flags(solid, t.blocks, options.min_thickness);
  if (std::any_of(thin.begin(), thin.end(), [](char c) { return c != 0; })) return fail("a sliver still");
  if (options.block_defect)
    for (const Block& b : t.blocks)
      if (!options.block_defect(b).empty()) return fail("a block failing the export's check");
  return t;
}

//! Stage 4 of remove_slivers() (and thicken_slivers()): the thickening of each sliver left (see
//! remove_slivers.h). Per sliver (in block order), along each frame axis
//! (the thinnest first: a rod gets thicker along one axis from a slab
//! along another), across each of
//! its two sides there that is a cut plane (a face of it lies in the plane
//! x_k = c of its box side), with depths delta = max(1.5 (m - t), m / 4), m
//! and 2m (m = min_thickness, t its mean chord along k): the slab beyond
//! that side over the sliver's footprint (its box across k) is taken from
//! every block whose box interior meets it, either as it is or, for a
//! neighbour milled across k, open towards the neighbour's tool side, or
//! through its whole extent along its milling axis (so that the pocket left
//! in it has no wall over its own material); then with the model in the
//! slab that no block holds (the interior may stay empty; also when no block
//! meets the slab). The first thickening try_thickening() accepts is kept. The
//! blocks make up the same solid as before, with at most some of the
//! model's interior added (the material moves between blocks exactly, then
//! is rounded once, cleaned as export cleans a block where that leaves
//! zero-area faces): nothing deviates but for that cleanup (1e-10 x scale).
void thicken_in_place(const Mesh& solid, SliverRemovalResult& r, const SliverRemovalOptions& options) {
  std::vector<char> flags = sliver_flags(solid, r.blocks, options.min_thickness);
  if (std::none_of(flags.begin(), flags.end(), [](char c) { return c != 0; })) return;
  const detail::SolidIndex index(solid);
  const double m = options.min_thickness;
  std::size_t total_tries = 0;  // over every sliver (options.max_thicken_tries_total)
  for (std::size_t s = 0; s < r.blocks.size(); ++s) {
    if (!flags[s]) continue;
    const Block& sliver = r.blocks[s];
    const BlockThickness th = block_thickness(sliver.mesh);
    std::vector<int> axes;
    for (int k = 0; k < 3; ++k) axes.push_back(k);  // a rod gets thicker along one axis by a slab along another
    std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) {
      return th.along[static_cast<std::size_t>(a)] < th.along[static_cast<std::size_t>(b)];
    });
    const std::vector<BoundingBox> boxes = detail::block_boxes(r.blocks);
    const BoundingBox& box = boxes[s];
    std::optional<Thickening> done;
    std::size_t tries = 0;
    std::map<std::string, int> failures;  // why the tries failed, for the log
    for (int k : axes) {
      const double t = th.along[static_cast<std::size_t>(k)];
      std::vector<double> depths{std::max(1.5 * (m - t), 0.25 * m), m, 2.0 * m};
      std::sort(depths.begin(), depths.end());
      depths.erase(std::unique(depths.begin(), depths.end()), depths.end());
      for (int side = 0; side < 2 && !done; ++side) {
        const double c = side == 0 ? box.min[k] : box.max[k];
        if (!has_face_in_plane(sliver.mesh, k, c)) continue;  // the input surface: nothing beyond it to take
        for (double delta : depths) {
          Box3 slab{box.min, box.max};
          if (side == 0) {
            slab.min[k] = c - delta;
            slab.max[k] = c;
          } else {
            slab.min[k] = c;
            slab.max[k] = c + delta;
          }
          const BoundingBox slab_box{slab.min, slab.max};
          std::vector<std::size_t> near;
          for (std::size_t j = 0; j < r.blocks.size(); ++j)
            if (j != s && detail::interiors_meet(boxes[j], slab_box)) near.push_back(j);
          // (through, interior): through 0, the slab over the footprint; 1,
          // open towards each neighbour's tool side; 2, through each
          // neighbour along its axis; interior: with the model's interior in
          // the slab that no block holds
          static constexpr std::array<std::pair<int, bool>, 5> kVariants{
              {{0, false}, {1, false}, {2, false}, {0, true}, {1, true}}};
          for (const auto& [through, interior] : kVariants) {
            if (done || tries >= options.max_thicken_tries || total_tries >= options.max_thicken_tries_total) break;
            if (!interior && near.empty()) continue;
            std::vector<Box3> regions;
            bool any_through = false;
            for (std::size_t j : near) {
              Box3 region = slab;
              const int d = axis_dimension(r.blocks[j].axis);
              if (through > 0 && d != k) {
                const double pad = std::max(1.0, boxes[j].diagonal());
                if (through == 2 || axis_sign(r.blocks[j].axis) < 0)
                  region.min[d] = std::min(region.min[d], boxes[j].min[d] - pad);
                if (through == 2 || axis_sign(r.blocks[j].axis) > 0)
                  region.max[d] = std::max(region.max[d], boxes[j].max[d] + pad);
                any_through = true;
              }
              regions.push_back(region);
            }
            if (through > 0 && !any_through) continue;
            std::string why;
            ++tries;
            ++total_tries;
            done = try_thickening(solid, r.blocks, r.filled, s, near, regions, interior ? &index : nullptr, slab,
                                  options, why);
            if (!done) ++failures[why];
          }
          if (done) break;
        }
      }
      if (done) break;
    }
    if (!done) {
      if (options.progress) {
        std::string list;
        int n = 0;
        for (const auto& [what, count] : failures) {
          list += (list.empty() ? "" : ", ") + what + " (" + std::to_string(count) + ")";
          n += count;
        }
        options.progress->info("sliver block " + std::to_string(s + 1) + ": no thickening" +
                               (n == 0 ? std::string(total_tries >= options.max_thicken_tries_total
                                                         ? " (this stage's budget of tries is spent)"
                                                         : " (no side of it is a cut face)")
                                       : " in " + std::to_string(n) + " tries: " + list));
      }
      continue;
    }
    if (options.progress) {
      std::string names;
      for (std::size_t i = 1; i < done->replaced.size(); ++i)
        names += (names.empty() ? "" : ", ") + std::to_string(done->replaced[i] + 1);
      options.progress->info("sliver block " + std::to_string(s + 1) + " thickened with material of block(s) " +
                             names + ": " + std::to_string(done->blocks.size()) + " block(s) for " +
                             std::to_string(done->replaced.size()) + ", no sliver, nothing deviates");
    }
    // Replace: the thickened sliver at s, each neighbour by its first piece
    // (or removed when none is left), the other pieces appended.
    std::vector<std::optional<std::size_t>> first(r.blocks.size());  // new block taking each old block's place
    first[s] = 0;
    std::vector<std::size_t> extra;
    for (std::size_t b = 1, i = 1; i < done->replaced.size(); ++i)
      for (std::size_t p = 0; p < done->pieces[i]; ++p, ++b) {
        if (p == 0)
          first[done->replaced[i]] = b;
        else
          extra.push_back(b);
      }
    std::vector<Block> next;
    std::vector<char> next_filled, next_flags;
    const auto add = [&](Block block, char fill, char flag) {
      next.push_back(std::move(block));
      if (!r.filled.empty()) next_filled.push_back(fill);
      next_flags.push_back(flag);
    };
    std::size_t at = 0;
    for (std::size_t i = 0; i < r.blocks.size(); ++i) {
      const bool changed = std::find(done->replaced.begin(), done->replaced.end(), i) != done->replaced.end();
      if (i == s) at = next.size();
      if (!changed)
        add(std::move(r.blocks[i]), r.filled.empty() ? char{0} : r.filled[i], flags[i]);
      else if (first[i])
        add(std::move(done->blocks[*first[i]]), done->filled.empty() ? char{0} : done->filled[*first[i]], 0);
    }
    for (std::size_t b : extra) add(std::move(done->blocks[b]), done->filled.empty() ? char{0} : done->filled[b], 0);
    r.blocks = std::move(next);
    r.filled = std::move(next_filled);
    flags = std::move(next_flags);
    ++r.num_thickened;
    // the cleanup's tolerance, as a merge within T records it (at T = 0 the
    // export cleans every block at that tolerance anyway, as merge_blocks()'s unions)
    if (options.tolerance > 0) r.max_deviation = std::max(r.max_deviation, done->moved);
    s = at;  // the blocks before it may have moved down: go on after the thickened sliver
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

namespace {

//! The checks of remove_slivers() and thicken_slivers() (`name`) on their options.
void check_options(const char* name, const SliverRemovalOptions& options, std::size_t num_blocks) {
  const std::string n = name;
  if (!(options.min_thickness > 0) || !std::isfinite(options.min_thickness))
    throw InvalidArgumentError(n + ": min_thickness must be a positive length (model units)");
  if (!(options.tolerance >= 0) || !std::isfinite(options.tolerance))
    throw InvalidArgumentError(n + ": the tolerance must be a length >= 0");
  if (!(options.error_fraction > 0 && options.error_fraction < 1))
    throw InvalidArgumentError(n + ": the error fraction must lie in (0, 1)");
  if (options.filled && options.filled->size() != num_blocks)
    throw InvalidArgumentError(n + ": one filled flag per block expected");
}

}  // namespace

SliverRemovalResult remove_slivers(const Mesh& solid, std::vector<Block> blocks, const SliverRemovalOptions& options) {
  check_options("remove_slivers", options, blocks.size());
  StageScope stage(options.progress, "slivers");
  SliverRemovalResult result;
  if (options.filled) result.filled = *options.filled;
  std::vector<char> flags = sliver_flags(solid, blocks, options.min_thickness);
  result.num_found = static_cast<std::size_t>(std::count(flags.begin(), flags.end(), char{1}));
  result.num_left = result.num_found;
  if (result.num_found == 0) {
    result.blocks = std::move(blocks);
    return result;
  }
  if (options.tolerance == 0) {
    // Exact: nothing may deviate, so only the thickening (4.), which moves
    // material between blocks exactly.
    result.blocks = std::move(blocks);
    if (options.thicken) {
      thicken_in_place(solid, result, options);
      flags = sliver_flags(solid, result.blocks, options.min_thickness);
      result.num_left = static_cast<std::size_t>(std::count(flags.begin(), flags.end(), char{1}));
    }
    if (options.progress && result.num_found > 0)
      options.progress->info(std::to_string(result.num_found) + " sliver block(s) thinner than " +
                             std::to_string(options.min_thickness) + " model units where the model is thicker" +
                             (options.thicken ? ": " + std::to_string(result.num_thickened) +
                                                    " thickened with a neighbour's material, " +
                                                    std::to_string(result.num_left) + " left"
                                              : std::string(" (exact: nothing may deviate)")));
    if (options.progress && result.num_left > 0 && options.thicken)  // else the caller goes on (step 9c)
      options.progress->warn(std::to_string(result.num_left) + " sliver block(s) thinner than " +
                             std::to_string(options.min_thickness) +
                             " model units where the model is thicker (exact decomposition: nothing may deviate, "
                             "they are kept; validate check 9 lists them)");
    return result;
  }
  result.blocks = std::move(blocks);
  const double error = options.error_fraction * options.tolerance;
  // 1. and 2.: drops, then merges, of every sliver.
  drop_and_merge(solid, result, options, nullptr);
  // 3. Splits of each sliver left across a plane of its own faces, when
  //    the drops and merges then remove every thin piece.
  split_slivers(solid, result, options);
  // 4. Thickening of each sliver left with its neighbours' material, exactly.
  if (options.thicken) thicken_in_place(solid, result, options);
  flags = sliver_flags(solid, result.blocks, options.min_thickness);
  result.num_left = static_cast<std::size_t>(std::count(flags.begin(), flags.end(), char{1}));
  if (options.progress) {
    options.progress->info(std::to_string(result.num_found) + " sliver block(s) thinner than " +
                           std::to_string(options.min_thickness) + " model units: " +
                           std::to_string(result.num_merged) + " merged into a neighbour and " +
                           std::to_string(result.num_dropped) + " dropped within the tolerance (" +
                           std::to_string(result.num_split) + " split first), " +
                           (options.thicken ? std::to_string(result.num_thickened) +
                                                  " thickened with a neighbour's material, "
                                            : std::string()) +
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
                               "): no drop: " + why +
                                   "; no merge with a neighbour within T; no split of it whose thin pieces go" +
                                   (options.thicken ? "; no thickening" : ""));
      }
    }
    if (result.num_left > 0 && options.thicken)  // else the caller goes on (decompose's step 9c)
      options.progress->warn(std::to_string(result.num_left) +
                             " sliver block(s) no drop, merge, split or thickening removes within the tolerance are kept "
                             "(validate check 9 lists them)");
  }
  return result;
}

SliverRemovalResult thicken_slivers(const Mesh& solid, std::vector<Block> blocks, const SliverRemovalOptions& options) {
  check_options("thicken_slivers", options, blocks.size());
  StageScope stage(options.progress, "slivers");
  SliverRemovalResult result;
  if (options.filled) result.filled = *options.filled;
  result.blocks = std::move(blocks);
  std::vector<char> flags = sliver_flags(solid, result.blocks, options.min_thickness);
  result.num_found = static_cast<std::size_t>(std::count(flags.begin(), flags.end(), char{1}));
  result.num_left = result.num_found;
  if (result.num_found == 0) return result;
  thicken_in_place(solid, result, options);
  flags = sliver_flags(solid, result.blocks, options.min_thickness);
  result.num_left = static_cast<std::size_t>(std::count(flags.begin(), flags.end(), char{1}));
  if (options.progress)
    options.progress->info(std::to_string(result.num_found) + " sliver block(s) left: " +
                           std::to_string(result.num_thickened) + " thickened with a neighbour's material, " +
                           std::to_string(result.num_left) + " left");
  return result;
}

}  // namespace subfab
