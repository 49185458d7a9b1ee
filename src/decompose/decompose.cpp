// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/decompose.h"

#include <algorithm>
#include <cstdio>
#include <array>
#include <chrono>
#include <functional>
#include <cstdint>
#include <unordered_set>
#include <numeric>
#include <optional>
#include <cmath>
#include <sstream>
#include <string>

#include <unordered_map>

#include "geometry/rotate_accurately.h"
#include "subfab/checks/require_closed_solid.h"
#include "decompose/block_pairs_detail.h"
#include "decompose/box_pieces.h"
#include "geometry/solid_index.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/compute_field.h"
#include "subfab/fidelity/find_infeasible_features.h"
#include "subfab/geometry/coordinate_rounding.h"
#include "subfab/decompose/grow_boxes.h"
#include "subfab/decompose/merge_blocks.h"
#include "decompose/single_precision_cleanup.h"
#include "subfab/decompose/export_decomposition.h"
#include "subfab/decompose/finalize_blocks.h"
#include "subfab/validate/validate_decomposition.h"
#include "subfab/decompose/merge_within_tolerance.h"
#include "subfab/decompose/mill_within_tolerance.h"
#include "subfab/decompose/tolerance_allowances.h"
#include "subfab/decompose/orient_mesh.h"
#include "subfab/decompose/remove_slivers.h"
#include "subfab/validate/find_slivers.h"
#include "subfab/validate/measure_fill_deviation.h"
#include "subfab/validate/milled_shape.h"
#include "subfab/decompose/resolve_overlaps.h"
#include "subfab/decompose/select_cover.h"
#include "subfab/decompose/snap_and_shrink.h"

namespace subfab {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void check_options(const DecomposeOptions& o) {
  if (std::isnan(o.max_height_fraction) || o.max_height_fraction <= 0)
    throw InvalidArgumentError("--max-height must be a positive fraction of the bounding-box diagonal");
  if (std::isnan(o.max_height_abs) || o.max_height_abs <= 0)
    throw InvalidArgumentError("--max-height-abs must be a positive length in model units");
  if (!(o.grid_factor > 0) || !std::isfinite(o.grid_factor))
    throw InvalidArgumentError("--grid-factor must be a positive number");
  if (o.machine && !((o.machine->array() > 0).all() && o.machine->allFinite()))
    throw InvalidArgumentError("--machine sizes must be positive numbers in model units");
  if (!(o.cover_time_limit_s > 0)) throw InvalidArgumentError("the cover time limit must be positive");
  if (!(o.max_deviation > 0) || !std::isfinite(o.max_deviation))
    throw InvalidArgumentError("--max-deviation must be a positive fraction of the bounding-box diagonal");
  if (std::isnan(o.tolerance_fraction) || o.tolerance_fraction < 0 || !std::isfinite(o.tolerance_fraction))
    throw InvalidArgumentError("--tolerance must be a fraction of the bounding-box diagonal >= 0");
  if (std::isnan(o.tolerance_abs) || o.tolerance_abs < 0)
    throw InvalidArgumentError("--tolerance-abs must be a length in model units >= 0");
  if (o.tolerance_rounds < 1) throw InvalidArgumentError("tolerance_rounds must be at least 1");
  if (std::isnan(o.tolerance_exact_margin)) throw InvalidArgumentError("tolerance_exact_margin must be a number");
  if (!(o.tolerance_floor_scale >= 0) || !std::isfinite(o.tolerance_floor_scale))
    throw InvalidArgumentError("tolerance_floor_scale must be a non-negative finite number");
  if (o.tolerance_depth_fractions.empty() ||
      !std::all_of(o.tolerance_depth_fractions.begin(), o.tolerance_depth_fractions.end(),
                   [](double q) { return q > 0 && std::isfinite(q); }))
    throw InvalidArgumentError("tolerance_depth_fractions must be positive finite numbers (at least one)");
  if (!(o.fallback_tolerance_fraction >= 0) || !std::isfinite(o.fallback_tolerance_fraction))
    throw InvalidArgumentError("the fallback tolerance must be a fraction of the bounding-box diagonal >= 0");
  if (!(o.max_precision_snap >= 0) || !std::isfinite(o.max_precision_snap))
    throw InvalidArgumentError("the precision snap's cap must be a fraction of the bounding-box diagonal >= 0");
  if (!(o.fallback_min_carve_gain >= 0 && o.fallback_min_carve_gain < 1))
    throw InvalidArgumentError("the fallback's minimum carve gain must lie in [0, 1)");
  if (!(o.sliver_thickness >= 0) || !std::isfinite(o.sliver_thickness))
    throw InvalidArgumentError("the sliver thickness must be a fraction of the bounding-box diagonal >= 0");
  for (std::size_t i = 0; i < o.tolerance_overhang_ladder_deg.size(); ++i) {
    const double deg = o.tolerance_overhang_ladder_deg[i];
    if (!(deg > 0 && deg <= 45) || (i > 0 && !(deg > o.tolerance_overhang_ladder_deg[i - 1])))
      throw InvalidArgumentError("tolerance_overhang_ladder_deg must be increasing angles in (0, 45] degrees");
  }
  if (!(o.tolerance_ladder_slack >= 0 && o.tolerance_ladder_slack <= 1))
    throw InvalidArgumentError("tolerance_ladder_slack must lie in [0, 1]");
  overhang_sine(o.max_overhang_deg);  // throws on a value outside [0, 45] degrees
}

//! The early-failure message: what, where (input coordinates), why, what to do.
std::string infeasible_message(const FeasibilityResult& infeasible, const Mesh& input, bool oriented) {
  std::ostringstream msg;
  msg << "no exact height-field decomposition exists in " << (oriented ? "any orientation tried" : "the input frame")
      << ": " << infeasible.num_edges << " crease edge(s) and " << infeasible.num_vertices
      << " corner vertex(es) cannot be covered by any axis-aligned height-field block, however finely the mesh is "
         "refined one-to-four ("
      << describe_infeasible_features(infeasible, input, 3)
      << "; input coordinates";
  if (infeasible.num_splittable_vertices > 0)
    msg << "; " << infeasible.num_splittable_vertices
        << " of the vertices would become coverable if the triangles there were split along the coordinate "
           "planes through the vertex, which the local refinement does not do";
  msg << "). At a crease the two faces have no common milling axis among +-x, +-y, +-z (each "
         "faces away from every axis the other faces) and every block holding the edge also holds both faces; at a "
         "corner every block holding a face's tip also meets a face of the same vertex that faces away from that "
         "block's axis (a thin spike or cone tip no axis sees). ";
  if (oriented)
    msg << "Try --no-orient (the input frame may be free of them), turn the model so that such creases lie in "
           "axis-aligned planes, or smooth/remesh the model there.";
  else
    msg << "Try without --no-orient (another orientation may be free of them), turn the model so that such "
           "creases lie in axis-aligned planes, or smooth/remesh the model there.";
  return msg.str();
}

//! The repaired canonical mesh in input coordinates: vertices that are
//! canonical input vertices get the input's exact coordinates back, the
//! others are turned back with one rounding.
Mesh repaired_in_input_frame(const Mesh& input, const Mesh& canonical, const Mesh& repaired,
                             const Eigen::Matrix3d& rotation) {
  struct Hash {
    std::size_t operator()(const Vec3& v) const {
      return std::hash<double>{}(v.x()) ^ (std::hash<double>{}(v.y()) * 31) ^ (std::hash<double>{}(v.z()) * 131);
    }
  };
  std::unordered_map<Vec3, std::size_t, Hash> input_vertex;
  for (std::size_t i = 0; i < canonical.num_vertices() && i < input.num_vertices(); ++i)
    input_vertex.emplace(canonical.vertices[i], i);
  const Eigen::Matrix3d back = rotation.transpose();
  Mesh out;
  out.faces = repaired.faces;
  out.vertices.reserve(repaired.num_vertices());
  for (const Vec3& c : repaired.vertices) {
    const auto it = input_vertex.find(c);
    out.vertices.push_back(it != input_vertex.end() ? input.vertices[it->second] : detail::rotate_accurately(back, c));
  }
  return out;
}

//! Stages 2 to 6 of decompose() on `solid` (canonical frame): fields,
//! grow, cover, snap, resolve and carve, under the overhang allowances
//! `allowed` (per face of `solid`, with their base floors; nullptr: none).
//! Sets result.canonical to
//! the refined solid and adds the stages' statistics and times to `result`.
//! `input_spacing`: the field grid keeps the input's spacing (as after a
//! repair) although `solid` is a part of it with other edges (a carved
//! piece: its cut faces have long edges).
std::vector<Block> carve_stages(const Mesh& solid, const OverhangAllowances* allowances, const Mesh& input,
                                const DecomposeOptions& options, DecomposeResult& result, bool input_spacing = false,
                                const std::vector<HeightBox>* carried = nullptr) {
  Progress* progress = options.progress;
  const double overhang = options.max_overhang_deg;
  const Vec3 machine = options.machine ? *options.machine : Vec3::Constant(std::numeric_limits<double>::infinity());
  const std::vector<std::uint8_t>* allowed = allowances ? &allowances->bits : nullptr;
  const std::vector<std::array<double, 3>>* floors = allowances ? &allowances->floors : nullptr;
  // 2. fields (4.3.2); a face allowed in some box counts as facing (the
  //    field only guides grow, which checks the floors exactly)
  std::array<HeightField, 6> fields;
  {
    StageScope stage(progress, "field");
    const auto t = Clock::now();
    FieldOptions o;
    o.grid_factor = options.grid_factor;
    if (result.repaired_input || input_spacing)  // the grid keeps the input's spacing (the repair adds small faces)
      o.grid_factor *= average_edge_length(input) / average_edge_length(solid);
    o.max_height = result.max_height;
    o.max_overhang_deg = overhang;
    o.progress = progress;
    o.allowed_overhangs = allowed;
    fields = compute_fields(solid, o);
    result.timings.field += seconds_since(t);
  }

  // 3. grow (4.3.2, Appendix B; local refinement 4.3.5)
  GrowResult grown;
  {
    StageScope stage(progress, "grow");
    const auto t = Clock::now();
    GrowOptions o;
    o.grid_factor = options.grid_factor;
    o.max_height = result.max_height;
    o.machine_size = machine;
    o.fields = &fields;
    o.allowed_overhangs = allowed;
    o.overhang_floors = floors;
    o.max_overhang_deg = overhang;
    o.carried = carried;
    o.progress = progress;
    grown = grow_boxes(solid, o);
    result.num_grown_boxes = grown.boxes.size();
    result.num_refined_faces = grown.num_refined_faces;
    result.timings.grow += seconds_since(t);
  }
  result.canonical = grown.mesh;
  // The allowances of the refined mesh: a face inherits its parent's.
  std::vector<std::uint8_t> grown_allowed;
  std::vector<std::array<double, 3>> grown_floors;
  if (allowances)
    for (int parent : grown.parent_face) {
      grown_allowed.push_back(allowances->bits[static_cast<std::size_t>(parent)]);
      grown_floors.push_back(allowances->floors[static_cast<std::size_t>(parent)]);
    }
  const std::vector<std::uint8_t>* refined_allowed = allowances ? &grown_allowed : nullptr;
  const std::vector<std::array<double, 3>>* refined_floors = allowances ? &grown_floors : nullptr;

  // 4. minimal cover (4.3.2, ILP with CBC), 5. snap and shrink (4.3.4) and
  //    resolve overlaps (4.3.3: conflict graph, cycle splits, carve order),
  //    for two covers: one minimising blocks (each box costs its connected
  //    surface pieces, box_pieces.h) and one minimising boxes (the thesis).
  //    Covers of the same size can need very different numbers of cycle
  //    splits, so the carve order whose boxes add up to fewer pieces is kept
  //    (ties: the first). Snap and resolve are timed as "resolve".
  std::vector<HeightBox> ordered;
  {
    const detail::SolidIndex piece_index(result.canonical, overhang_sine(overhang), refined_allowed, refined_floors);
    const std::vector<int> neighbours = detail::face_neighbours(result.canonical);
    const bool one_piece_each = std::all_of(grown.num_pieces.begin(), grown.num_pieces.end(), [](int p) { return p == 1; });
    std::size_t best_pieces = std::numeric_limits<std::size_t>::max();
    for (const bool by_pieces : {true, false}) {
      if (!by_pieces && one_piece_each) break;  // the same cover again
      std::vector<HeightBox> selected;
      CoverResult cover;
      {
        StageScope stage(progress, "cover");
        const auto t = Clock::now();
        CoverOptions o;
        o.time_limit_s = options.cover_time_limit_s;
        o.progress = progress;
        o.preference.reserve(grown.boxes.size());
        for (const HeightBox& b : grown.boxes) o.preference.push_back(b.box.volume());
        if (by_pieces) o.cost = grown.num_pieces;
        cover = select_cover(grown.covered, grown.mesh.num_faces(), o);
        for (int b : cover.selected) selected.push_back(grown.boxes[static_cast<std::size_t>(b)]);
        result.timings.cover += seconds_since(t);
      }
      const std::size_t num_selected = selected.size();
      {
        StageScope stage(progress, "snap");
        const auto t = Clock::now();
        SnapShrinkOptions o;
        o.snap_distance = average_edge_length(input) * options.grid_factor;
        o.max_height = result.max_height;
        o.machine_size = machine;
        o.max_overhang_deg = overhang;
        o.allowed_overhangs = refined_allowed;
        o.overhang_floors = refined_floors;
        o.progress = progress;
        selected = snap_and_shrink(result.canonical, std::move(selected), o).boxes;
        result.timings.resolve += seconds_since(t);
      }
      StageScope stage(progress, "resolve");
      const auto t = Clock::now();
      ResolveOptions o;
      o.max_overhang_deg = overhang;
      o.allowed_overhangs = refined_allowed;
      o.overhang_floors = refined_floors;
      o.progress = progress;
      ResolveResult r = resolve_overlaps(result.canonical, std::move(selected), o);
      std::vector<std::size_t> pieces(r.ordered.size());
      parallel_for(0, r.ordered.size(), [&](std::size_t i) {
        pieces[i] = std::max<std::size_t>(1, detail::surface_pieces(piece_index, neighbours, r.ordered[i]).size());
      });
      const std::size_t total = std::accumulate(pieces.begin(), pieces.end(), std::size_t{0});
      if (progress)
        progress->info(std::string("cover by ") + (by_pieces ? "pieces" : "boxes") + ": " +
                       std::to_string(num_selected) + " boxes, " + std::to_string(r.ordered.size()) +
                       " in carve order, " + std::to_string(total) + " pieces");
      if (total < best_pieces) {
        best_pieces = total;
        ordered = std::move(r.ordered);
        result.num_selected_boxes = num_selected;
        result.cover_optimal = cover.optimal;
        result.num_ordered_boxes = ordered.size();
        result.num_cycle_splits = r.num_splits;
      }
      result.timings.resolve += seconds_since(t);
    }
  }

  // 6. carve (exact booleans)
  StageScope stage(progress, "carve");
  const auto t = Clock::now();
  CarveOptions co;
  co.max_height = result.max_height;
  co.machine_size = machine;
  co.max_overhang_deg = overhang;
  co.allowed_overhangs = refined_allowed;
  co.overhang_floors = refined_floors;
  co.progress = progress;
  CarveResult carved = carve_blocks(result.canonical, ordered, co);
  result.num_carved_blocks = carved.blocks.size();
  result.ordered_boxes = std::move(ordered);
  result.timings.carve += seconds_since(t);
  return std::move(carved.blocks);
}

//! Lowers by one level (a smaller depth fraction, then none) the
//! allowances for the axis of every failed block, on the faces allowed for
//! it whose bounding box meets the block's (a block fails where the
//! material left under its allowed faces is too deep or collides), except
//! the pinned ones (`pinned`, per face, may be empty: the allowances a thin
//! feature needs, see pinned_allowances()). Where the block failed by
//! sampled points farther than T (milled.far_points) and `margin` >= 0
//! (model units), only the faces over those points step down: those whose
//! box, widened across the axis by `margin`, holds a point's projection (on
//! a grid of cells of that size), so a large block failing in one corner
//! keeps its allowances elsewhere (issue 17, session 35). Returns the number
//! of allowances lowered.
std::size_t lower_allowances(const Mesh& solid, const MillToleranceResult& milled, const std::vector<std::uint8_t>& allowed,
                             const std::vector<std::uint8_t>& pinned, double margin,
                             std::vector<std::array<std::uint8_t, 3>>& level) {
  std::vector<BoundingBox> face_boxes(solid.num_faces());
  for (std::size_t f = 0; f < solid.num_faces(); ++f)
    for (int v : solid.faces[f]) face_boxes[f].extend(solid.vertices[static_cast<std::size_t>(v)]);
  std::vector<std::array<std::uint8_t, 3>> lower(solid.num_faces(), {0, 0, 0});
  const auto lowerable = [&](std::size_t f, std::uint8_t bit) {
    return (allowed[f] & bit) && !(!pinned.empty() && (pinned[f] & bit));
  };
  for (std::size_t i = 0; i < milled.blocks.size(); ++i) {
    if (milled.failures[i].empty()) continue;
    const BoundingBox box = bounding_box(milled.blocks[i].mesh);
    const int k = axis_dimension(milled.blocks[i].axis);
    const auto bit = static_cast<std::uint8_t>(1u << k);
    const std::vector<Vec3>* far = i < milled.far_points.size() && margin >= 0 ? &milled.far_points[i] : nullptr;
    std::size_t located = 0;
    if (far && !far->empty()) {
      // The fill at a far point p lies under the faces above p along the
      // axis: the faces whose boxes, widened across it by `margin`, hold
      // p's projection (a grid of cells of that size over the points).
      const int u = (k + 1) % 3, v = (k + 2) % 3;
      const double cell = margin > 0 ? margin : std::max(box.diagonal() * 1e-9, 1e-300);
      std::unordered_set<std::uint64_t> cells;
      const auto key = [](std::int64_t a, std::int64_t b) {
        return (static_cast<std::uint64_t>(a) << 32) ^ static_cast<std::uint64_t>(b & 0xffffffff);
      };
      const auto index = [&](double x, int d) { return static_cast<std::int64_t>(std::floor((x - box.min[d]) / cell)); };
      for (const Vec3& p : *far) cells.insert(key(index(p[u], u), index(p[v], v)));
      for (std::size_t f = 0; f < solid.num_faces(); ++f) {
        if (!lowerable(f, bit) || !detail::boxes_touch(face_boxes[f], box)) continue;
        const BoundingBox& fb = face_boxes[f];
        const std::int64_t u0 = index(fb.min[u] - margin, u), u1 = index(fb.max[u] + margin, u);
        const std::int64_t v0 = index(fb.min[v] - margin, v), v1 = index(fb.max[v] + margin, v);
        bool over = false;
        for (std::int64_t a = u0; a <= u1 && !over; ++a)
          for (std::int64_t b = v0; b <= v1 && !over; ++b) over = cells.count(key(a, b)) > 0;
        if (over) {
          lower[f][static_cast<std::size_t>(k)] = 1;
          ++located;
        }
      }
    }
    if (located > 0) continue;
    for (std::size_t f = 0; f < solid.num_faces(); ++f)
      if (lowerable(f, bit) && detail::boxes_touch(face_boxes[f], box)) lower[f][static_cast<std::size_t>(k)] = 1;
  }
  std::size_t lowered = 0;
  for (std::size_t f = 0; f < solid.num_faces(); ++f)
    for (std::size_t k = 0; k < 3; ++k)
      if (lower[f][k]) {
        ++level[f][k];
        ++lowered;
      }
  return lowered;
}

//! Stage 7's options (merge_blocks()): the run's height limit, machine and
//! overhang allowance; shared by the stage and by step 9c's merges of a
//! piece decomposed again.
MergeOptions merge_options(const DecomposeOptions& options, const DecomposeResult& result) {
  MergeOptions mo;
  mo.max_height = result.max_height;
  mo.machine_size = options.machine ? *options.machine : Vec3::Constant(std::numeric_limits<double>::infinity());
  mo.max_overhang_deg = result.max_overhang_deg;
  return mo;
}

//! The result a piece decomposed again on its own (carve_stages()) starts
//! from: the run's height limit and overhang allowance, tolerance `tolerance`.
DecomposeResult piece_result(const DecomposeResult& result, double tolerance) {
  DecomposeResult sub;
  sub.max_height = result.max_height;
  sub.max_overhang_deg = result.max_overhang_deg;
  sub.tolerance = tolerance;
  return sub;
}

//! Stage 7 of decompose(): exact merges of touching blocks (4.3.4
//! post-processing) into result.blocks; `filled` (per block, may be empty)
//! follows the merges.
void merge_stage(std::vector<Block> blocks, std::vector<char>& filled, const DecomposeOptions& options,
                 DecomposeResult& result) {
  Progress* progress = options.progress;
  {
    StageScope stage(progress, "merge");
    const auto t = Clock::now();
    if (options.merge) {
      MergeOptions mo = merge_options(options, result);
      mo.progress = progress;
      MergeResult merged = merge_blocks(std::move(blocks), mo);
      result.blocks = std::move(merged.blocks);
      result.num_merges = merged.num_merges;
      if (!filled.empty()) {  // a union sticks out when one of its parts does
        std::vector<char> merged_filled(result.blocks.size(), 0);
        for (std::size_t b = 0; b < merged.parts.size(); ++b)
          for (std::size_t part : merged.parts[b]) merged_filled[b] = static_cast<char>(merged_filled[b] | filled[part]);
        filled = std::move(merged_filled);
      }
    } else {
      result.blocks = std::move(blocks);
    }
    result.timings.carve += seconds_since(t);
  }
}

//! Within a tolerance (issue 17): the allowances `allowed` (per face of
//! `solid`) restricted to the faces around the features `infeasible` (the
//! stars of their vertices: the only faces their exact tests look at), when
//! they make every one of them coverable (find_infeasible_features() with
//! the allowances, exact; checked again with the restriction); empty when
//! some feature stays infeasible under them. These are the allowances a
//! thin feature needs instead of the thin-feature repair: the stages must
//! keep them (decompose() never lowers them).
std::vector<std::uint8_t> pinned_allowances(const Mesh& solid, const FeasibilityResult& infeasible,
                                            const std::vector<std::uint8_t>& allowed) {
  FeasibilityOptions fo;
  fo.allowed_overhangs = &allowed;
  if (!find_infeasible_features(solid, fo).feasible()) return {};
  std::vector<char> at_feature(solid.num_vertices(), 0);
  for (const InfeasibleFeature& feature : infeasible.features)
    for (int v : {feature.vertex0, feature.vertex1})
      if (v >= 0) at_feature[static_cast<std::size_t>(v)] = 1;
  std::vector<std::uint8_t> pinned(solid.num_faces(), 0);
  for (std::size_t f = 0; f < solid.num_faces(); ++f)
    for (int v : solid.faces[f])
      if (at_feature[static_cast<std::size_t>(v)]) pinned[f] = allowed[f];
  fo.allowed_overhangs = &pinned;
  if (!find_infeasible_features(solid, fo).feasible()) return {};
  return pinned;
}

//! The thin-feature repair gave up at tolerance 0 (decompose() may then
//! decompose within options.fallback_tolerance_fraction instead).
class RepairGaveUp : public AlgorithmError {
 public:
  using AlgorithmError::AlgorithmError;
};

//! A round under allowances carved too many blocks to beat the exact
//! decomposition made first (DecomposeOptions::tolerance_exact_margin).
class NotFewerThanExact : public AlgorithmError {
 public:
  using AlgorithmError::AlgorithmError;
};

//! The whole re-decomposition within the fallback tolerance was given up
//! after a round whose carve had too many blocks to pay off
//! (options.fallback_min_carve_gain; decompose()).
class FallbackGivenUp : public AlgorithmError {
 public:
  using AlgorithmError::AlgorithmError;
};

//! Stage 1b of decompose(): the local repair of the features `infeasible`
//! of result.canonical (4.3.5); replaces result.canonical by the repaired
//! solid and sets result.repaired_input and result.repair. Throws
//! RepairGaveUp when the repair fails at tolerance 0, AlgorithmError within
//! a tolerance.
void repair_stage(const Mesh& input, const FeasibilityResult& infeasible, const DecomposeOptions& options,
                  DecomposeResult& result) {
  Progress* progress = options.progress;
  StageScope repair_stage(progress, "repair");
  const auto tr = Clock::now();
  RepairOptions ro;
  ro.max_deviation = options.max_deviation;
  ro.progress = progress;
  if (progress)
    progress->warn(std::to_string(infeasible.size()) + " feature(s) no height-field block can cover in the " +
                   (options.orient ? "chosen" : "input") + " frame (" +
                   describe_infeasible_features(infeasible, input, 3) +
                   "; input coordinates): repairing them by local smoothing (--exact refuses instead)");
  RepairResult repaired;
  try {
    repaired = repair_infeasible_features(result.canonical, ro);
  } catch (const AlgorithmError& e) {
    std::string within;
    if (result.tolerance > 0)
      within = " (within the tolerance, the faces there may not lean past vertical: their undercuts are deeper "
               "than the tolerance allows, or the blocks holding them failed the measure)";
    const std::string message = std::string("the local repair of infeasible features failed: ") + e.what() + within +
                                ". Without it: " + infeasible_message(infeasible, input, options.orient);
    if (result.tolerance > 0) throw AlgorithmError(message);
    throw RepairGaveUp(message);
  }
  Mesh in_input = repaired_in_input_frame(input, result.canonical, repaired.mesh, result.rotation);
  // The rounding back to the input frame must keep a valid solid.
  require_closed_solid_result(in_input, "the repaired mesh is not a valid solid in the input frame: ");
  result.repair = repaired.report;
  result.canonical = std::move(repaired.mesh);
  result.num_input_vertices = result.canonical.num_vertices();
  result.repaired_input = std::move(in_input);
  result.timings.repair += seconds_since(tr);
}

//! Stage 1's precision snap (OrientOptions::precision_snap_tolerance): the
//! chosen frame is feasible only with the input's coordinates snapped within
//! the file's own rounding, so the blocks decompose that snapped solid. Sets
//! result.repaired_input to it in input coordinates (vertices no snap moved
//! keep the input's exact coordinates, the others are turned back) and
//! result.repair's deviations to the largest and mean vertex move (a bound
//! of the Hausdorff distance: same faces). Throws AlgorithmError when the
//! snapped solid is not a valid solid in the input frame.
void precision_snap_stage(const Mesh& input, double diagonal, DecomposeResult& result) {
  // Only the vertices no snap moved keep the input's coordinates: one the
  // 1e-9 snap moved but the precision snap left there would come back as
  // the input's (up to that snap off its canonical plane: rotated couplingdown
  // in float32 had base faces off its block's base).
  const Mesh plain = rotate_into_frame(input, result.rotation, 0.0);
  Mesh in_input = repaired_in_input_frame(input, plain, result.canonical, result.rotation);
  require_closed_solid_result(in_input, "the input snapped to its coordinates' precision is not a valid solid: ");
  double largest = 0, sum = 0;
  std::size_t moved = 0;
  for (std::size_t i = 0; i < input.num_vertices(); ++i) {
    const double d = (in_input.vertices[i] - input.vertices[i]).norm();
    largest = std::max(largest, d);
    sum += d;
    moved += d > 0;
  }
  result.repair = RepairReport{};
  result.repair.bbox_diagonal = diagonal;
  result.repair.max_deviation = largest;
  result.repair.mean_deviation = input.num_vertices() > 0 ? sum / static_cast<double>(input.num_vertices()) : 0.0;
  result.num_snapped_vertices = moved;
  result.repaired_input = std::move(in_input);
}

//! The undercut depths of `solid` for the allowances (tolerance_allowances.h).
std::vector<std::array<double, 3>> depths_within(const Mesh& solid, const DecomposeOptions& options,
                                                 const DecomposeResult& result) {
  const std::vector<double>& fractions = options.tolerance_depth_fractions;
  ToleranceAllowanceOptions ao;
  ao.tolerance = result.tolerance;
  ao.depth_fraction = *std::max_element(fractions.begin(), fractions.end());
  ao.max_height = result.max_height;
  return undercut_depths(solid, ao);
}

//! The milled shapes of `blocks`, measured within result.tolerance
//! (mill_within_tolerance()), timed as "tolerance".
MillToleranceResult mill_stage(const Mesh& solid, std::vector<Block> blocks, const DecomposeOptions& options,
                               DecomposeResult& result, const std::vector<char>* measure = nullptr,
                               const std::vector<double>* known_deviation = nullptr, bool stop_at_first_failure = false,
                               bool locate_failures = false, MillCache* cache = nullptr) {
  StageScope stage(options.progress, "mill");
  const auto t = Clock::now();
  MillToleranceOptions mo;
  mo.locate_failures = locate_failures;
  mo.tolerance = result.tolerance;
  mo.measure = measure;
  mo.known_deviation = known_deviation;
  mo.stop_at_first_failure = stop_at_first_failure;
  mo.cache = cache;
  mo.progress = options.progress;
  MillToleranceResult milled = mill_within_tolerance(solid, std::move(blocks), mo);
  result.timings.tolerance += seconds_since(t);
  return milled;
}

//! The end of stages_within_tolerance() when its last round under
//! allowances still leaves blocks beyond the tolerance (issue 17): instead
//! of decomposing the whole model again without allowances, only the
//! failing blocks are decomposed again, each on its own carved piece: first
//! under the piece's own allowances at the smallest depth fraction (stages
//! 2-6 on the piece alone, its undercut depths measured in it: a deeper or
//! no allowance where a neighbour lies under a face, never a larger one),
//! and where a block of that fails too, exactly (no allowances: exact
//! height fields inside the piece, which add no material and collide with
//! nothing). The other blocks are kept milled. After each pass the blocks
//! are milled and measured again, the deviation only of the blocks within
//! reach of a change (without a neighbour's fill, the faces a fill had
//! against it lie on the model's surface; the measure of a block reads the
//! input faces within T of its box and the blocks within T of those, so a
//! block whose box widened by 2 T + twice the longest edge of `solid`
//! misses every changed box keeps its measure). Each pass takes at least
//! one block a level further (round, piece within T, exact), so it ends.
//! `carved`: the round's carved pieces, `milled`: their measure. Sets
//! `blocks`, `filled` and result.num_blocks_decomposed_in_place (the round's blocks
//! replaced). Returns false, changing nothing in `blocks`, when a piece is
//! not a closed 2-manifold, holds a crease or spike no exact block covers,
//! or its exact decomposition fails: the caller then takes the exact path.
bool replace_failed_blocks(const Mesh& solid, const std::vector<Block>& round_carved,
                           const MillToleranceResult& round_milled, const Mesh& input, const DecomposeOptions& options,
                           DecomposeResult& result, std::vector<Block>& blocks, std::vector<char>& filled,
                           MillCache* cache = nullptr) {
  Progress* progress = options.progress;
  std::vector<Block> carved = round_carved;
  MillToleranceResult milled = round_milled;
  std::vector<int> level(carved.size(), 0);  // 0: the round's piece, 1: a piece's block within T, 2: exact
  std::size_t replaced = 0;
  DecomposeOptions quiet = options;
  quiet.progress = nullptr;
  double longest_edge = 0;
  for (const auto& f : solid.faces)
    for (int k = 0; k < 3; ++k)
      longest_edge = std::max(longest_edge, (solid.vertices[static_cast<std::size_t>(f[k])] -
                                             solid.vertices[static_cast<std::size_t>(f[(k + 1) % 3])]).norm());
  const double margin = 2 * result.tolerance + 2 * longest_edge;
  const std::vector<double>& fractions = options.tolerance_depth_fractions;
  while (milled.num_failed() > 0) {
    std::vector<Block> next;
    std::vector<int> next_level;
    std::vector<char> is_new;
    std::vector<double> known;
    std::vector<BoundingBox> changed;  // boxes of the milled shapes replaced (the new blocks lie inside them)
    for (std::size_t i = 0; i < carved.size(); ++i) {
      if (milled.failures[i].empty()) {
        next.push_back(std::move(carved[i]));
        next_level.push_back(level[i]);
        is_new.push_back(0);
        known.push_back(milled.deviation[i]);
        continue;
      }
      // The carved piece as a solid of its own: rounding to doubles leaves
      // caps and zero-area faces (export cleans them the same way), which
      // the stages' exact booleans must not be given.
      Mesh piece = carved[i].mesh;
      std::string why;
      if (level[i] >= 2) why = "an exact block failed the measure";  // never: exact blocks add nothing
      try {
        if (why.empty()) {
          clean_rounded_block(piece, axis_direction(carved[i].axis), FinalizeOptions{}.relative_tolerance * rounding_scale(solid));
          require_closed_solid_result(piece, "its carved piece is not a clean solid: ");
        }
      } catch (const std::exception& e) {
        why = e.what();
      }
      if (why.empty() && !find_infeasible_features(piece).feasible())
        why = "its carved piece holds a crease or spike no exact block covers";
      std::vector<Block> parts;
      int part_level = 2;
      if (why.empty()) {
        DecomposeResult sub = piece_result(result, result.tolerance);
        try {
          OverhangAllowances allowed;
          if (level[i] == 0) {
            const std::vector<std::array<std::uint8_t, 3>> smallest(
                piece.num_faces(), std::array<std::uint8_t, 3>{static_cast<std::uint8_t>(fractions.size() - 1),
                                                               static_cast<std::uint8_t>(fractions.size() - 1),
                                                               static_cast<std::uint8_t>(fractions.size() - 1)});
            allowed = allowances_with_floors(piece, depths_within(piece, options, sub), smallest, fractions,
                                             result.tolerance, options.tolerance_floor_scale);
          }
          part_level = count_allowed_faces(allowed.bits) > 0 ? 1 : 2;
          parts = carve_stages(piece, part_level == 1 ? &allowed : nullptr, input, quiet, sub, /*input_spacing=*/true);
        } catch (const std::exception& e) {  // any failure here only sends the model to the exact path
          why = std::string("its decomposition failed: ") + e.what();
        }
        DecomposeTimings& t = result.timings;
        t.field += sub.timings.field;
        t.grow += sub.timings.grow;
        t.cover += sub.timings.cover;
        t.resolve += sub.timings.resolve;
        t.carve += sub.timings.carve;
      }
      if (!why.empty()) {
        if (progress)
          progress->info("block " + std::to_string(i + 1) + " beyond the tolerance cannot be decomposed again in "
                         "place (" + why + "): decomposing the whole model again");
        return false;
      }
      if (progress)
        progress->info("block " + std::to_string(i + 1) + " beyond the tolerance (" + milled.failures[i] +
                       ") replaced by the " + std::to_string(parts.size()) + " block(s) of its carved piece " +
                       (part_level == 1 ? "within the tolerance" : "exactly"));
      if (level[i] == 0) ++replaced;
      changed.push_back(bounding_box(milled.blocks[i].mesh));
      for (Block& b : parts) {
        next.push_back(std::move(b));
        next_level.push_back(part_level);
        is_new.push_back(1);
        known.push_back(0.0);
      }
    }
    // which kept blocks' measures can have changed: boxes from the milled shapes of the last pass
    std::vector<BoundingBox> old_boxes;
    for (std::size_t i = 0; i < carved.size(); ++i)
      if (milled.failures[i].empty()) old_boxes.push_back(bounding_box(milled.blocks[i].mesh));
    std::vector<char> measure(next.size(), 1);
    for (std::size_t k = 0, kept = 0; k < next.size(); ++k) {
      if (is_new[k]) continue;
      BoundingBox reach = old_boxes[kept++];
      reach.min -= Vec3::Constant(margin);
      reach.max += Vec3::Constant(margin);
      measure[k] = std::any_of(changed.begin(), changed.end(),
                               [&](const BoundingBox& c) { return detail::boxes_touch(reach, c); })
                       ? 1
                       : 0;
    }
    carved = next;  // the pieces again: mill_stage() makes the milled shapes from them
    level = std::move(next_level);
    milled = mill_stage(solid, std::move(next), options, result, &measure, &known, false, false, cache);
  }
  blocks = std::move(milled.blocks);
  filled = std::move(milled.filled);
  result.deviation_bound = milled.max_deviation;
  result.num_blocks_decomposed_in_place = replaced;
  return true;
}

//! Blocks of `piece`, the union of the blocks `group` (a sliver and one or
//! two of its neighbours, in `blocks`), decomposed again within the tolerance T = result.tolerance
//! > 0 (recarve_slivers(); issue 17, "no slivers"): their exact
//! re-decomposition gives the sliver back where the carve's box planes stay
//! where they were (elephant.off, turbine.off at 1e-3). Under the piece's
//! own allowances at each depth fraction in turn (the largest first;
//! stages 2-6 on the piece, then merge_blocks() with `mo`), each block is
//! replaced by its milled shape, and the first level is kept whose blocks
//! are at most as many as the group's, none a sliver (`min_thickness`), each milled shape a
//! closed height field that keeps the model within T of `solid`
//! (FillDeviationMeter: measure + error <= T, with the blocks that stick
//! out; only measured where it adds material or the pair stuck out),
//! overlaps no other block (validate's exact volume check, 1e-6) and passes
//! `defect` (the export's check). `filled`: per block, 1 where it sticks
//! out of the solid; `bound`: the largest measured deviation (model units).
//! `why` receives what each level failed on (for the log).
struct WithinParts {
  std::vector<Block> blocks;
  std::vector<char> filled;
  double bound = 0.0;
};
std::optional<WithinParts> recarve_within(const Mesh& solid, const Mesh& piece, const Mesh& input,
                                          const DecomposeOptions& quiet, const DecomposeResult& result,
                                          const std::vector<Block>& blocks, const std::vector<char>& alive,
                                          const std::vector<char>& sticks_out, const std::vector<std::size_t>& group,
                                          double min_thickness, const MergeOptions& mo,
                                          const std::function<std::string(const Block&)>& defect, std::string& why) {
  const double tolerance = result.tolerance;
  const std::vector<double>& fractions = quiet.tolerance_depth_fractions;
  const auto in_group = [&](std::size_t k) { return std::find(group.begin(), group.end(), k) != group.end(); };
  const bool group_out = std::any_of(group.begin(), group.end(), [&](std::size_t k) { return sticks_out[k] != 0; });
  const auto skip = [&](std::size_t k) { return in_group(k) || !alive[k]; };
  const std::vector<BoundingBox> boxes = detail::block_boxes(blocks);
  const std::vector<double> volumes = detail::block_volumes(blocks);
  std::vector<const Mesh*> sticking;  // the blocks the meter's model adds to the input
  for (std::size_t k = 0; k < blocks.size(); ++k)
    if (!skip(k) && sticks_out[k]) sticking.push_back(&blocks[k].mesh);
  const FillDeviationMeter meter(solid);
  for (std::size_t level = 0; level < fractions.size(); ++level) {
    DecomposeResult sub = piece_result(result, tolerance);
    std::vector<Block> parts;
    const auto failed = [&](const std::string& what) {
      why += (why.empty() ? "" : ", ") + std::string("at ") + std::to_string(fractions[level]) + " T " + what;
    };
    try {
      const auto l = static_cast<std::uint8_t>(level);
      const std::vector<std::array<std::uint8_t, 3>> levels(piece.num_faces(), std::array<std::uint8_t, 3>{l, l, l});
      const OverhangAllowances allowed = allowances_with_floors(piece, depths_within(piece, quiet, sub), levels,
                                                                fractions, tolerance, quiet.tolerance_floor_scale);
      if (count_allowed_faces(allowed.bits) == 0) break;  // none at a smaller fraction either: the exact carve
      parts = merge_blocks(carve_stages(piece, &allowed, input, quiet, sub, /*input_spacing=*/true), mo).blocks;
    } catch (const std::exception& e) {
      failed(std::string("failed (") + e.what() + ")");
      continue;
    }
    if (parts.empty() || parts.size() > group.size()) {
      failed(std::to_string(parts.size()) + " blocks");
      continue;
    }
    WithinParts w;
    bool ok = true;
    for (const Block& p : parts) {
      MilledShape m;
      try {
        m = milled_shape(p.mesh, axis_direction(p.axis));
      } catch (const std::exception&) {
        ok = false;
        break;
      }
      if (m.is_block) {
        w.blocks.push_back(p);
        w.filled.push_back(static_cast<char>(group_out));
        continue;
      }
      if (!check_closed_solid(m.mesh).ok() || !is_height_field(m.mesh, axis_direction(p.axis))) {
        ok = false;
        break;
      }
      w.blocks.push_back(Block{std::move(m.mesh), p.axis, p.source_box});
      w.filled.push_back(1);
    }
    if (!ok) {
      failed("a milled shape that is no closed height field");
      continue;
    }
    const std::vector<char> thin = sliver_flags(solid, w.blocks, min_thickness);
    if (std::any_of(thin.begin(), thin.end(), [](char c) { return c != 0; })) {
      failed(std::to_string(w.blocks.size()) + " blocks, one a sliver");
      continue;
    }
    const FillDeviationOptions fo{.reach = tolerance, .error = 0.05 * tolerance};
    for (std::size_t i = 0; i < w.blocks.size() && ok; ++i) {
      const Block& b = w.blocks[i];
      if (defect && !defect(b).empty()) {
        failed("a block failing the export's check");
        ok = false;
      }
      if (!ok || !w.filled[i]) continue;  // an exact block inside the piece: nothing added, nothing to collide with
      std::vector<const Mesh*> others = sticking;
      for (std::size_t o = 0; o < w.blocks.size(); ++o)
        if (o != i && w.filled[o]) others.push_back(&w.blocks[o].mesh);
      std::optional<std::vector<BoundingBox>> fill;
      if (!group_out && b.mesh.num_faces() > 0) fill = fill_columns(parts[i].mesh, b.mesh, b.axis);
      const FillDeviation dev = fill ? meter.measure_fill(b.mesh, others, *fill, fo) : meter.measure(b.mesh, others, fo);
      if (!dev.failure.empty() || !(dev.bound() <= tolerance)) {
        failed(dev.failure.empty() ? "a milled shape " + std::to_string(dev.bound() / tolerance) + " T from the input"
                                   : "a deviation not measured (" + dev.failure + ")");
        ok = false;
        continue;
      }
      w.bound = std::max(w.bound, dev.bound());
      ok = !detail::overlaps_a_block(b.mesh, blocks, boxes, volumes, skip, MillToleranceOptions{}.collision_tolerance);
      if (ok)  // and the other new blocks
        ok = !detail::overlaps_a_block(b.mesh, w.blocks, detail::block_boxes(w.blocks), detail::block_volumes(w.blocks),
                                       [&](std::size_t o) { return o == i; }, MillToleranceOptions{}.collision_tolerance);
      if (!ok) failed("a milled shape overlapping another block");
    }
    if (ok) return w;
  }
  return std::nullopt;
}

//! Step 9c of decompose() (issue 17, "No slivers"; at any tolerance): a
//! sliver the sliver stage left (no drop, merge or split within T) is
//! decomposed again together with one block it touches, the largest first
//! (at most `max_neighbours`): their exact union (rounded, cleaned as
//! export cleans a block and checked as a closed solid without zero-area
//! faces or self-intersections) goes through stages 2-7 on its own,
//! exactly. Its blocks are exact height fields that make up the union, so
//! the model made, its deviation and the overlaps stay as they were (up to
//! the cleanup's 1e-10 x scale); the pair is replaced when that gives at
//! most two blocks, none a sliver (sliver_flags(), validate's rule) and
//! each passing the export's check `defect`. When no neighbour alone
//! does, the sliver is tried with two neighbours at once (pairs of the
//! three largest; their union, kept when at most three blocks, none a
//! sliver). Last, a sliver none of these removes takes the first exact
//! re-decomposition that gave one block more than its group, none a
//! sliver, if its group is still whole after every sliver had its turn
//! (one block more rather than a block no machine can hold), when
//! `last_resort` (decompose() first runs it without, then the thickening,
//! then with it for the slivers left). Within a tolerance (T > 0),
//! when the exact blocks are not kept, the union is decomposed again under
//! its own allowances (recarve_within(): milled, measured within T, checked
//! for collisions; its deviation bound raises result.deviation_bound). A
//! new block sticks out of the solid when one of the pair did or its milled
//! shape adds material (`filled`, per block, follows when it has one entry
//! per block or a new block sticks out; else left empty). Returns the
//! number of slivers removed; result.blocks and `filled` updated. Timed by
//! the caller.
std::size_t recarve_slivers(const Mesh& solid, const Mesh& input, const DecomposeOptions& options,
                            DecomposeResult& result, std::vector<char>& filled, double min_thickness,
                            const std::function<std::string(const Block&)>& defect, bool last_resort,
                            std::size_t max_neighbours = 4) {
  Progress* progress = options.progress;
  DecomposeOptions quiet = options;
  quiet.progress = nullptr;
  std::vector<Block>& blocks = result.blocks;
  const bool track_filled = filled.size() == blocks.size();  // else none sticks out yet: `filled` stays empty
                                                             // unless a block made within T does
  std::vector<char> sticks_out = track_filled ? filled : std::vector<char>(blocks.size(), 0);
  const std::size_t n0 = blocks.size();
  const std::vector<char> sliver = sliver_flags(solid, blocks, min_thickness);
  std::vector<char> alive(n0, 1);
  std::size_t removed = 0;
  // The group's blocks (group[0] the sliver) replaced by `parts`.
  const auto replace = [&](const std::vector<std::size_t>& group, std::vector<Block> parts,
                           const std::vector<char>& parts_out, const std::string& names, const std::string& how) {
    if (progress)
      progress->info("sliver block " + std::to_string(group[0] + 1) + " and its neighbour" +
                     (group.size() > 2 ? "s " : " ") + names + " decomposed again together, " + how + ": " +
                     std::to_string(parts.size()) + " block(s), no sliver");
    for (std::size_t k : group) alive[k] = 0;
    for (std::size_t p = 0; p < parts.size(); ++p) {
      blocks.push_back(std::move(parts[p]));
      sticks_out.push_back(parts_out[p]);
      alive.push_back(1);
    }
    ++removed;
  };
  // Per sliver, the first exact re-decomposition with one block more than
  // its group, none a sliver: taken after every sliver had its attempts,
  // where none kept the count and the group is still whole.
  struct Spare {
    std::vector<std::size_t> group;
    std::vector<Block> parts;
    std::vector<char> parts_out;
    std::string names;
  };
  std::vector<Spare> spares;
  for (std::size_t s = 0; s < n0; ++s) {
    if (!sliver[s] || !alive[s]) continue;
    const BoundingBox sb = bounding_box(blocks[s].mesh);
    std::vector<std::pair<double, std::size_t>> near;  // (-volume, index): the largest first, ties by index
    for (std::size_t j = 0; j < blocks.size(); ++j)
      if (j != s && alive[j] && detail::boxes_touch(sb, bounding_box(blocks[j].mesh)))
        near.emplace_back(-signed_volume(blocks[j].mesh), j);
    std::sort(near.begin(), near.end());
    if (near.size() > max_neighbours) near.resize(max_neighbours);
    std::optional<Spare> spare;  // this sliver's
    // One attempt: the sliver with the blocks `others` (its neighbours),
    // their union decomposed again into at most as many blocks as it joins.
    const auto attempt = [&](const std::vector<std::size_t>& others) {
      std::vector<std::size_t> group{s};
      group.insert(group.end(), others.begin(), others.end());
      std::string names;
      for (std::size_t k : others) names += (names.empty() ? "" : " and ") + std::to_string(k + 1);
      // why a group is not kept, in the log (elephant.off at 1e-3: its two
      // slivers stay slivers, or become 3 blocks, with each neighbour)
      const auto rejected = [&](const std::string& why) {
        if (progress)
          progress->info("sliver block " + std::to_string(s + 1) + " with its neighbour" +
                         (others.size() > 1 ? "s " : " ") + names + ": " + why);
      };
      std::vector<const Mesh*> members;
      for (std::size_t k : group) members.push_back(&blocks[k].mesh);
      detail::RoundingReport rounding;
      std::optional<Mesh> u = detail::exact_block_union(members, nullptr, rounding);
      if (!u) {
        rejected("their exact union is not one solid");
        return false;
      }
      std::vector<Block> parts;
      DecomposeResult sub = piece_result(result, result.tolerance);
      const MergeOptions mo = merge_options(options, result);
      Mesh piece = std::move(*u);
      bool feasible = false;
      try {
        clean_rounded_block(piece, axis_direction(blocks[others.front()].axis),
                            FinalizeOptions{}.relative_tolerance * rounding_scale(solid));
        require_closed_solid_result(piece, "the union of a sliver and its neighbour is not a clean solid: ");
        feasible = find_infeasible_features(piece).feasible();
        if (feasible) parts = merge_blocks(carve_stages(piece, nullptr, input, quiet, sub, /*input_spacing=*/true), mo).blocks;
      } catch (const std::exception& e) {  // this group cannot be decomposed again: the next one
        rejected(std::string("not decomposed again (") + e.what() + ")");
        return false;
      }
      const bool group_out = std::any_of(group.begin(), group.end(), [&](std::size_t k) { return sticks_out[k] != 0; });
      std::string why;  // why the exact blocks are not kept
      if (parts.empty()) {
        why = feasible ? "no exact blocks" : "their union holds a crease or spike no exact block covers";
      } else if (parts.size() > group.size()) {
        why = std::to_string(parts.size()) + " blocks exactly (at most " + std::to_string(group.size()) + " kept)";
        // one block more, none a sliver: the last resort (below)
        if (!spare && parts.size() == group.size() + 1) {
          const std::vector<char> thin = sliver_flags(solid, parts, min_thickness);
          if (std::none_of(thin.begin(), thin.end(), [](char c) { return c != 0; }) &&
              !(defect && std::any_of(parts.begin(), parts.end(), [&](const Block& b) { return !defect(b).empty(); })))
            spare = Spare{group, parts, std::vector<char>(parts.size(), static_cast<char>(group_out)), names};
        }
      } else {
        const std::vector<char> thin = sliver_flags(solid, parts, min_thickness);
        if (std::any_of(thin.begin(), thin.end(), [](char c) { return c != 0; }))
          why = std::to_string(parts.size()) + " block(s) exactly, one a sliver still";
        else if (defect && std::any_of(parts.begin(), parts.end(), [&](const Block& b) { return !defect(b).empty(); }))
          why = "a block fails the export's check";
      }
      std::vector<char> parts_out(parts.size(), static_cast<char>(group_out));
      std::string how = "exactly";
      if (!why.empty() && result.tolerance > 0) {
        // within the tolerance: the piece's own allowances, the milled shapes measured
        std::string within_why;
        std::optional<WithinParts> w = recarve_within(solid, piece, input, quiet, result, blocks, alive, sticks_out,
                                                      group, min_thickness, mo, defect, within_why);
        if (w) {
          parts = std::move(w->blocks);
          parts_out = std::move(w->filled);
          result.deviation_bound = std::max(result.deviation_bound, w->bound);
          how = "within the tolerance (deviation bound " + std::to_string(w->bound / result.tolerance) + " T)";
          why.clear();
        } else {
          why += "; within the tolerance: " + (within_why.empty() ? std::string("no face may lean") : within_why);
        }
      }
      if (!why.empty()) {
        rejected(why);
        return false;
      }
      replace(group, std::move(parts), parts_out, names, how);
      return true;
    };
    bool done = false;
    for (std::size_t a = 0; a < near.size() && !done; ++a) done = attempt({near[a].second});
    // With two neighbours at once (the three largest, in pairs): a union
    // that holds more of the material around the sliver lets the carve put
    // its box planes elsewhere (spot.off at 5e-4: block 1 with 29, or with 2,
    // gave a sliver back at every level).
    const std::size_t two = std::min<std::size_t>(near.size(), 3);
    for (std::size_t a = 0; a < two && !done; ++a)
      for (std::size_t b = a + 1; b < two && !done; ++b) done = attempt({near[a].second, near[b].second});
    if (!done && spare && last_resort) spares.push_back(std::move(*spare));
  }
  // Last resort: one block more, exactly, rather than a sliver no machine
  // can hold (elephant.off at 1e-3: block 35 with its neighbours 43 and 109).
  for (Spare& sp : spares) {
    if (!std::all_of(sp.group.begin(), sp.group.end(), [&](std::size_t k) { return alive[k] != 0; })) continue;
    replace(sp.group, std::move(sp.parts), sp.parts_out, sp.names, "exactly, one block more");
  }
  if (removed == 0) return 0;
  std::vector<Block> kept;
  std::vector<char> kept_filled;
  for (std::size_t i = 0; i < blocks.size(); ++i)
    if (alive[i]) {
      kept.push_back(std::move(blocks[i]));
      kept_filled.push_back(sticks_out[i]);
    }
  blocks = std::move(kept);
  // a block made within the tolerance may stick out where none did before
  if (track_filled || std::any_of(kept_filled.begin(), kept_filled.end(), [](char c) { return c != 0; }))
    filled = std::move(kept_filled);
  return removed;
}

//! The block count a carve reaches when it has far more blocks than `best`
//! (DecomposeOptions::tolerance_exact_margin `margin` >= 0): max(best + 2,
//! ceil((1 + margin) best)). Rounds under allowances against the exact
//! decomposition and the overhang ladder against the best so far.
std::size_t far_more_blocks(std::size_t best, double margin) {
  const auto b = static_cast<double>(best);
  return static_cast<std::size_t>(std::max(b + 2, std::ceil((1 + margin) * b)));
}

//! Adds the time the stages 2-6 spent between `before` and `after` (field,
//! grow, cover, resolve, carve) to `t`: a result kept from two paths counts
//! both.
void add_stage_times(DecomposeTimings& t, const DecomposeTimings& after, const DecomposeTimings& before) {
  t.field += after.field - before.field;
  t.grow += after.grow - before.grow;
  t.cover += after.cover - before.cover;
  t.resolve += after.resolve - before.resolve;
  t.carve += after.carve - before.carve;
}

//! Stages 2-6 of decompose() within a tolerance (issue 17) on `solid`:
//! under the allowances of the faces whose undercut is within it, then
//! every block replaced by its milled shape and measured; where one fails,
//! its allowances are lowered and the stages run again, the last round
//! under the pinned allowances only (`pinned`: those a thin feature needs;
//! empty or all zero: none, the exact path). Sets `blocks` and `filled`.
//! Returns false when the blocks still fail the measure under the pinned
//! allowances alone (never when none are pinned). `carve_limit` > 0: throws
//! FallbackGivenUp when a round under allowances carves at least that many
//! blocks (decompose()'s rule for the re-decomposition within the fallback
//! tolerance), before its blocks are milled and measured. `exact_limit` > 0:
//! the same with NotFewerThanExact (the exact decomposition made first has
//! so few blocks that this round cannot pay off).
bool stages_within_tolerance(const Mesh& solid, const std::vector<std::array<double, 3>>& depths,
                             const std::vector<std::uint8_t>& pinned, const Mesh& input,
                             const DecomposeOptions& options, DecomposeResult& result, std::vector<Block>& blocks,
                             std::vector<char>& filled, std::size_t carve_limit, std::size_t exact_limit) {
  Progress* progress = options.progress;
  const std::vector<double>& fractions = options.tolerance_depth_fractions;
  std::vector<std::array<std::uint8_t, 3>> level(solid.num_faces(), {0, 0, 0});
  const double floor_scale = options.tolerance_floor_scale;
  const bool with_floors = floor_scale > 0;
  OverhangAllowances allowed = allowances_with_floors(solid, depths, level, fractions, result.tolerance, floor_scale);
  OverhangAllowances last;
  last.bits = pinned.empty() ? std::vector<std::uint8_t>(solid.num_faces(), 0) : pinned;
  last.floors.assign(solid.num_faces(), {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                                         -std::numeric_limits<double>::infinity()});
  const auto count_everywhere = [](const OverhangAllowances& a) {
    return count_allowed_faces(a.bits) - count_floored_faces(a);
  };
  result.num_floored_faces = count_floored_faces(allowed);
  result.num_allowed_faces = count_everywhere(allowed);
  if (progress)
    progress->info(std::to_string(result.num_allowed_faces) + " of " + std::to_string(solid.num_faces()) +
                   " faces may lean past vertical (undercut within " + std::to_string(fractions.front()) +
                   " x the tolerance)" +
                   (with_floors ? ", " + std::to_string(result.num_floored_faces) +
                                      " more in boxes whose base lies close enough under them"
                                : std::string()));
  std::vector<HeightBox> carried;  // the boxes of the blocks that passed the last round (tolerance_carry_boxes)
  MillCache cache;                 // the blocks the rounds milled: a block carved again unchanged is not milled again
  // The rounds lower allowances only where blocks fail and carry the passing
  // blocks' boxes over (session 35); when they would end on the pinned
  // allowances alone (the exact path), the rounds run once more as before:
  // every allowed face in a failing block's box lowered, every round grown
  // afresh (egea at 8.3e-2: the first way's second round collides and its
  // last cannot be decomposed in place; the second way passes in 2 rounds).
  bool refined = options.tolerance_carry_boxes || options.tolerance_locate_margin >= 0;
  const OverhangAllowances initial = allowed;
  const auto second_chance = [&](int& round) {
    if (!refined) return false;
    refined = false;
    level.assign(solid.num_faces(), {0, 0, 0});
    allowed = initial;
    carried.clear();
    round = -1;
    if (progress)
      progress->info("the rounds again, each grown afresh, lowering the allowances in the whole box of each failing block");
    return true;
  };
  for (int round = 0;; ++round) {
    const std::size_t num_allowed = count_allowed_faces(allowed.bits);
    blocks = carve_stages(solid, num_allowed > 0 ? &allowed : nullptr, input, options, result, false,
                          num_allowed > 0 && !carried.empty() ? &carried : nullptr);
    if (carve_limit > 0 && blocks.size() >= carve_limit)
      throw FallbackGivenUp("round " + std::to_string(round + 1) + " carved " + std::to_string(blocks.size()) +
                            " blocks, at least " + std::to_string(carve_limit));
    if (exact_limit > 0 && num_allowed > 0 && blocks.size() >= exact_limit)
      throw NotFewerThanExact("round " + std::to_string(round + 1) + " under allowances carved " +
                              std::to_string(blocks.size()) + " blocks, at least " + std::to_string(exact_limit));
    if (num_allowed == 0) return true;
    ++result.num_tolerance_rounds;
    const bool last_round = round + 1 >= options.tolerance_rounds;
    std::vector<Block> carved;  // the last round's pieces, for replace_failed_blocks()
    if (last_round && options.tolerance_local_exact) carved = blocks;
    const double margin = refined ? options.tolerance_locate_margin * result.tolerance : -1.0;
    MillToleranceResult milled =
        mill_stage(solid, std::move(blocks), options, result, nullptr, nullptr, false, !last_round && margin >= 0, &cache);
    if (milled.num_failed() == 0) {
      blocks = std::move(milled.blocks);
      filled = std::move(milled.filled);
      result.deviation_bound = milled.max_deviation;
      return true;
    }
    if (last_round && options.tolerance_local_exact) {
      if (progress)
        progress->info(std::to_string(milled.num_failed()) + " block(s) beyond the tolerance after " +
                       std::to_string(round + 1) + " round(s): decomposing their carved pieces again, each on its own");
      if (replace_failed_blocks(solid, carved, milled, input, options, result, blocks, filled, &cache)) return true;
    }
    if (allowed == last) return false;  // nothing left to lower
    // A round that carried boxes over and fails only by collisions: the
    // milled shapes collide where a carried box meets a box grown around
    // it, not because an allowance is too large (egea at 8.3e-2: round 2's
    // carried block collides with the one grown again next to it; lowering
    // the whole box of the colliding block, twice, ended on the exact
    // path). The same allowances are tried once more, grown afresh.
    const bool only_collisions = [&] {
      for (std::size_t i = 0; i < milled.failures.size(); ++i)
        if (!milled.failures[i].empty() && !milled.collided[i]) return false;
      return true;
    }();
    if (refined && !carried.empty() && only_collisions && !last_round) {
      carried.clear();
      if (progress)
        progress->info(std::to_string(milled.num_failed()) + " block(s) beyond the tolerance, every one by a collision "
                       "next to boxes carried over: the same allowances again, grown afresh");
      continue;
    }
    carried.clear();
    if (refined && options.tolerance_carry_boxes)
      for (std::size_t i = 0; i < milled.blocks.size(); ++i) {
        const int b = milled.blocks[i].source_box;
        if (milled.failures[i].empty() && !milled.collided[i] && b >= 0 &&
            static_cast<std::size_t>(b) < result.ordered_boxes.size())
          carried.push_back(result.ordered_boxes[static_cast<std::size_t>(b)]);
      }
    const OverhangAllowances before = allowed;
    if (last_round) {
      if (second_chance(round)) continue;
      allowed = last;
    } else {
      const OverhangAllowances previous = allowed;
      // A level down can leave a face's allowance as it was (its depth
      // within the next q x T too): step the same faces down until one
      // changes, or none is left to lower.
      for (std::size_t step = 0; step <= fractions.size() && allowed == previous; ++step) {
        if (lower_allowances(solid, milled, previous.bits, pinned, margin, level) == 0) break;
        allowed = allowances_with_floors(solid, depths, level, fractions, result.tolerance, floor_scale);
      }
      if (allowed == previous) {  // the failing blocks meet pinned allowances only
        if (second_chance(round)) continue;
        allowed = last;
      }
    }
    if (progress) {
      std::string first;
      for (std::size_t i = 0; i < milled.failures.size() && first.empty(); ++i)
        if (!milled.failures[i].empty()) first = "block " + std::to_string(i + 1) + ": " + milled.failures[i];
      progress->info(std::to_string(milled.num_failed()) + " block(s) beyond the tolerance (" + first + "); " +
                     std::to_string(count_changed_faces(before, allowed)) +
                     " faces get smaller allowances, decomposing again with " + std::to_string(count_everywhere(allowed)) +
                     " faces allowed (" + std::to_string(count_floored_faces(allowed)) + " more above base floors)");
    }
  }
}

//! Within a tolerance (issue 17): the overhang ladder. The depth allowances
//! (tolerance_allowances()) bound a face's undercut by the free length under
//! it, which can be far deeper than the fill of the block that holds it
//! (cube spike at 9.8e-4: the faces leaning 8 deg are allowed only above
//! base floors, 5 blocks; under a uniform 10 deg allowance 2 blocks, milled
//! shapes within 6.7e-4). When result's blocks deviate at most
//! options.tolerance_ladder_slack x T, the stages run again under each angle
//! of options.tolerance_overhang_ladder_deg in turn
//! (uniform_overhang_allowances(), the pinned allowances kept, on `solid`
//! from `base`); a carve with fewer blocks than the best so far is milled
//! and measured (mill_within_tolerance(), exact) and, when every milled
//! shape passes, merged (merge_blocks()) and kept if it still has fewer
//! blocks. The ladder ends at the first carve that fails the measure (a
//! larger angle lets the same faces lean farther; when the sampled lower
//! bound fails a block, nothing is measured exactly; else the failing
//! blocks' carved pieces are decomposed again in place,
//! replace_failed_blocks(), and the result kept if it has fewer blocks), at
//! one that passes with a deviation above the slack (no room left), at one
//! with at least max(B + 2, (1 + tolerance_exact_margin) B) blocks, B the
//! best so far (egea at 8.3e-2: 60 blocks at 5 deg against 6; the covers
//! of the larger angles took minutes), when a carve fails, or at one block.
//! Sets result (its timings include the ladder's) and `filled`.
void overhang_ladder_stage(const Mesh& solid, const std::vector<std::uint8_t>& pinned, const Mesh& input,
                           const DecomposeOptions& options, const DecomposeResult& base, DecomposeResult& result,
                           std::vector<char>& filled) {
  Progress* progress = options.progress;
  StageScope stage(progress, "overhang ladder");
  const auto g = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return std::string(text);
  };
  DecomposeTimings timings = result.timings;
  const auto add_times = [&](const DecomposeResult& cand) {
    add_stage_times(timings, cand.timings, base.timings);
    timings.tolerance += cand.timings.tolerance - base.timings.tolerance;
  };
  MillCache cache;  // blocks the angles carve alike are milled once
  for (const double deg : options.tolerance_overhang_ladder_deg) {
    if (result.blocks.size() <= 1) break;
    OverhangAllowances allowed = uniform_overhang_allowances(solid, deg);
    for (std::size_t f = 0; f < pinned.size() && f < allowed.bits.size(); ++f)
      allowed.bits[f] = static_cast<std::uint8_t>(allowed.bits[f] | pinned[f]);
    if (count_allowed_faces(allowed.bits) == 0) continue;
    const std::string at = "overhang ladder at " + g(deg) + " deg: ";
    DecomposeResult cand = base;
    try {
      std::vector<Block> carved = carve_stages(solid, &allowed, input, options, cand);
      if (carved.size() >= result.blocks.size()) {
        // far more blocks than the best: the larger angles are not expected
        // to cut that many (the rule of tolerance_exact_margin)
        const bool far = options.tolerance_exact_margin >= 0 &&
                         carved.size() >= far_more_blocks(result.blocks.size(), options.tolerance_exact_margin);
        if (progress)
          progress->info(at + std::to_string(carved.size()) + " blocks carved, not fewer than " +
                         std::to_string(result.blocks.size()) +
                         (far ? ": far more, the ladder ends" : ": not measured"));
        add_times(cand);
        if (far) break;
        continue;
      }
      const std::vector<Block> pieces = carved;  // for replace_failed_blocks()
      MillToleranceResult milled = mill_stage(solid, std::move(carved), options, cand, nullptr, nullptr, true, false, &cache);
      std::vector<Block> cand_blocks;
      std::vector<char> cand_filled;
      const bool failed = milled.num_failed() > 0;
      if (milled.stopped) {
        if (progress)
          progress->info(at + "a sampled point of a milled shape lies beyond the tolerance: the ladder ends");
        add_times(cand);
        break;
      }
      if (failed) {
        // the failing blocks' pieces decomposed again in place (as after the
        // last round); the angle still ends the ladder
        if (progress)
          progress->info(at + std::to_string(milled.num_failed()) + " of " + std::to_string(milled.blocks.size()) +
                         " milled shapes beyond the tolerance: decomposing their carved pieces again, each on its "
                         "own; the ladder ends here");
        if (!replace_failed_blocks(solid, pieces, milled, input, options, cand, cand_blocks, cand_filled, &cache)) {
          add_times(cand);
          break;
        }
      } else {
        cand_blocks = std::move(milled.blocks);
        cand_filled = std::move(milled.filled);
        cand.deviation_bound = milled.max_deviation;
      }
      const double deviation = cand.deviation_bound;
      merge_stage(std::move(cand_blocks), cand_filled, options, cand);
      add_times(cand);
      if (progress)
        progress->info(at + std::to_string(cand.blocks.size()) + " blocks within the tolerance (deviation bound " +
                       g(cand.deviation_bound / std::max(bounding_box(solid).diagonal(), 1e-300)) +
                       " x diagonal)" +
                       (cand.blocks.size() < result.blocks.size()
                            ? ", kept instead of " + std::to_string(result.blocks.size())
                            : ", not fewer than " + std::to_string(result.blocks.size())));
      if (cand.blocks.size() < result.blocks.size()) {
        cand.num_allowed_faces = result.num_allowed_faces;
        cand.num_floored_faces = result.num_floored_faces;
        cand.num_tolerance_rounds = result.num_tolerance_rounds + 1;
        cand.num_features_within_tolerance = result.num_features_within_tolerance;
        cand.tolerance_overhang_deg = deg;
        result = std::move(cand);
        filled = std::move(cand_filled);
      } else {
        ++result.num_tolerance_rounds;
      }
      if (failed) break;
      if (deviation > options.tolerance_ladder_slack * result.tolerance) {
        if (progress) progress->info(at + "its blocks leave the tolerance no room for a larger angle: the ladder ends");
        break;
      }
    } catch (const AlgorithmError& e) {
      if (progress) progress->info(at + "the stages failed (" + e.what() + "): the ladder ends");
      add_times(cand);
      break;
    }
  }
  result.timings = timings;
}

//! decompose() at options' tolerance, no fallback. At tolerance 0 with a
//! fallback tolerance (the command's default) and slivers left,
//! `*slivers_within` receives the same blocks with the sliver stage run
//! again within the fallback tolerance (remove_slivers_within_fallback()).
//! `carve_limit` > 0: within a tolerance, FallbackGivenUp is thrown when a
//! round of the stages carves at least that many blocks
//! (stages_within_tolerance()).
DecomposeResult decompose_once(const Mesh& input, const DecomposeOptions& options,
                               std::optional<DecomposeResult>* slivers_within = nullptr,
                               std::size_t carve_limit = 0) {
  Progress* progress = options.progress;
  const auto start = Clock::now();
  DecomposeResult result;
  result.num_input_vertices = input.num_vertices();
  const double diagonal = bounding_box(input).diagonal();
  result.max_height = std::min(options.max_height_fraction * diagonal, options.max_height_abs);
  result.max_overhang_deg = options.max_overhang_deg;
  result.tolerance = std::min(options.tolerance_fraction * diagonal, options.tolerance_abs);
  const Vec3 machine = options.machine ? *options.machine : Vec3::Constant(std::numeric_limits<double>::infinity());

  // 1. orient (4.3.1)
  FeasibilityResult infeasible;
  std::vector<std::array<double, 3>> depths;  // within a tolerance: per face of result.canonical
  std::vector<std::uint8_t> pinned;           // within a tolerance: the allowances the features need
  {
    StageScope stage(progress, "orient");
    const auto t = Clock::now();
    double precision_snap = 0;
    if (options.orient) {
      OrientOptions o;
      o.progress = progress;
      result.coordinate_rounding = coordinate_rounding(input);
      if (diagonal > 0)
        o.precision_snap_tolerance = std::min(4 * result.coordinate_rounding / diagonal, options.max_precision_snap);
      precision_snap = o.precision_snap_tolerance;
      OrientResult oriented = orient_mesh(input, o);
      result.rotation = oriented.rotation;
      result.frame_snap_tolerance = oriented.snap_tolerance;
      infeasible = std::move(oriented.infeasible);
    }
    result.canonical = rotate_into_frame(input, result.rotation, result.frame_snap_tolerance);
    // A part drawn in this frame (CAD): its flat faces are on the axes, and
    // coordinates within the file's rounding of each other are CAD noise
    // (fandisk: 9 vertices of its face x = 0 at x = 1e-6 and 2e-6 cost
    // blocks and a sliver). Snapped when that adds no infeasible feature.
    if (precision_snap > result.frame_snap_tolerance &&
        axis_aligned_area_fraction(result.canonical) >= OrientOptions{}.keep_frame_area) {
      Mesh snapped = snap_coordinates(result.canonical, precision_snap);
      if (snapped.vertices != result.canonical.vertices) {
        FeasibilityResult features = find_infeasible_features(snapped);
        if (features.size() <= infeasible.size()) {
          result.canonical = std::move(snapped);
          infeasible = std::move(features);
          result.frame_snap_tolerance = precision_snap;
          if (progress)
            progress->info("a part drawn in this frame: coordinates within the file's own rounding snapped (" +
                           std::to_string(precision_snap) + " x diagonal)");
        }
      }
    }
    if (result.frame_snap_tolerance > OrientOptions{}.snap_tolerance) precision_snap_stage(input, diagonal, result);
    if (!options.orient) infeasible = find_infeasible_features(result.canonical);
    result.timings.orient = seconds_since(t);
    // Within a tolerance, creases and spikes whose faces may lean past
    // vertical (their undercuts are within it) need no repair: the
    // allowances they need are pinned, and the blocks holding them are
    // milled and measured like any other (issue 17).
    if (result.tolerance > 0) {
      const auto tt = Clock::now();
      depths = depths_within(result.canonical, options, result);
      if (!infeasible.feasible()) {
        const std::vector<std::uint8_t> allowed =
            allowances_at(depths, std::vector<std::array<std::uint8_t, 3>>(depths.size(), {0, 0, 0}),
                          options.tolerance_depth_fractions, result.tolerance);
        pinned = pinned_allowances(result.canonical, infeasible, allowed);
        if (!pinned.empty()) {
          result.num_features_within_tolerance = infeasible.size();
          if (progress)
            progress->info(std::to_string(infeasible.size()) + " feature(s) no exact height-field block can cover (" +
                           describe_infeasible_features(infeasible, input, 3) +
                           "; input coordinates) are within the tolerance: " +
                           std::to_string(count_allowed_faces(pinned)) + " faces there may lean past vertical");
        }
      }
      result.timings.tolerance += seconds_since(tt);
    }
    // Fail before the expensive stages when no refinement can ever cover the
    // surface, unless the features are to be repaired (4.3.5).
    if (!infeasible.feasible() && pinned.empty() && !options.repair)
      throw AlgorithmError(infeasible_message(infeasible, input, options.orient));
  }
  // 1b. local repair of the infeasible features (4.3.5)
  const bool repaired = !infeasible.feasible() && pinned.empty();
  if (repaired) {
    repair_stage(input, infeasible, options, result);
    if (result.tolerance > 0) depths = depths_within(result.canonical, options, result);
  }

  // 2.-6. fields, grow, cover, snap, resolve, carve. Within a tolerance
  //    (issue 17): under the allowances of the faces whose undercut is
  //    within it, then every block replaced by its milled shape and
  //    measured; where one fails, its allowances are taken back and the
  //    stages run again (the last round with the pinned allowances only,
  //    without any when none are pinned: the exact path). When blocks still
  //    fail with the pinned allowances only, the features they cover are
  //    repaired after all (4.3.5) and the stages run on the repaired solid.
  Mesh solid = result.canonical;  // before grow's local refinement
  DecomposeResult base = result;  // before the stages (within a tolerance the exact path is made too)
  std::vector<Block> blocks;
  std::vector<char> filled;
  // Within a tolerance with no pinned allowance, the exact decomposition is
  // made first: a round under allowances that carves far more blocks is
  // then given up before its (costly) measure (tolerance_exact_margin). When
  // the exact stages fail, the tolerance's blocks are kept whatever they are.
  std::optional<DecomposeResult> exact_made;
  bool exact_failed = false, exact_kept = false;
  if (result.tolerance > 0 && count_allowed_faces(pinned) == 0 && options.tolerance_exact_margin >= 0) {
    try {
      exact_made = base;
      std::vector<char> none;
      merge_stage(carve_stages(solid, nullptr, input, options, *exact_made), none, options, *exact_made);
    } catch (const AlgorithmError& e) {
      if (progress) progress->info(std::string("the exact decomposition failed (") + e.what() + ")");
      exact_made.reset();
      exact_failed = true;
    }
  }
  if (result.tolerance > 0) {
    std::size_t exact_limit = 0;
    if (exact_made) exact_limit = far_more_blocks(exact_made->blocks.size(), options.tolerance_exact_margin);
    try {
      const bool passed =
          stages_within_tolerance(solid, depths, pinned, input, options, result, blocks, filled, carve_limit, exact_limit);
      if (exact_made) add_stage_times(result.timings, exact_made->timings, base.timings);
      if (!passed) {
        if (progress)
          progress->warn("the blocks holding the feature(s) within the tolerance fail its measure with only their "
                         "allowances: repairing the features instead");
        if (!options.repair)
          throw AlgorithmError("within the tolerance, the blocks holding the features no exact block can cover fail "
                               "the tolerance's measure (--exact refuses to repair them): " +
                               infeasible_message(infeasible, input, options.orient));
        result.num_features_within_tolerance = 0;
        pinned.clear();
        result.canonical = solid;  // the stages left grow's refinement of it there
        repair_stage(input, infeasible, options, result);
        solid = result.canonical;
        depths = depths_within(solid, options, result);
        base = result;
        filled.clear();
        stages_within_tolerance(solid, depths, pinned, input, options, result, blocks, filled, carve_limit, 0);
      }
    } catch (const NotFewerThanExact& e) {
      // the exact blocks, made first (the round's time counted too)
      if (progress)
        progress->info(std::string("within the tolerance: ") + e.what() + ", the exact decomposition has " +
                       std::to_string(exact_made->blocks.size()) + ": the exact blocks are kept, nothing measured");
      DecomposeResult exact = std::move(*exact_made);
      exact_made.reset();
      add_stage_times(exact.timings, result.timings, base.timings);
      exact.timings.tolerance += result.timings.tolerance - base.timings.tolerance;
      exact.num_tolerance_rounds = result.num_tolerance_rounds;
      exact.num_allowed_faces = result.num_allowed_faces;
      exact.num_floored_faces = result.num_floored_faces;
      result = std::move(exact);
      filled.clear();
      exact_kept = true;
    }
  } else {
    try {
      blocks = carve_stages(solid, nullptr, input, options, result);
    } catch (const AlgorithmError& e) {
      // The repaired solid is free of the features find_infeasible_features()
      // sees, but grow's refinement can still find no valid box at a corner
      // the repair left tight: its rounded midpoints tilt a sub-triangle of a
      // face parallel to an axis by a hair, which then faces away from that
      // axis (part.off in its input frame, --no-orient: a split of a vertical
      // face at the repaired corner faces a hair downwards and closes +z for
      // the faces around it). The repair has not made
      // the model decomposable, so at the default this is the repair giving
      // up: decompose() goes on within the fallback tolerance.
      if (!repaired || !options.repair) throw;
      throw RepairGaveUp(std::string("the thin-feature repair left a place no exact height-field block covers: ") +
                         e.what());
    }
  }

  // 7. merge (4.3.4 post-processing)
  if (!exact_kept) merge_stage(std::move(blocks), filled, options, result);
  // Within a tolerance, the allowances can also cost blocks (they change the
  // cover): the decomposition under the pinned allowances only (none: the
  // exact one) is made too and kept when it has no more blocks (and, with
  // pinned allowances, its milled shapes pass the measure).
  if (result.tolerance > 0 && !exact_kept && !exact_failed && (!filled.empty() || exact_made)) {
    const bool made_first = exact_made.has_value();  // its time is already in result's
    DecomposeResult exact = made_first ? std::move(*exact_made) : base;
    const bool any_pinned = count_allowed_faces(pinned) > 0;
    OverhangAllowances pinned_only;
    if (any_pinned) {
      pinned_only.bits = pinned;
      pinned_only.floors.assign(solid.num_faces(), {-std::numeric_limits<double>::infinity(),
                                                    -std::numeric_limits<double>::infinity(),
                                                    -std::numeric_limits<double>::infinity()});
    }
    std::vector<char> exact_filled;
    bool usable = true;
    std::vector<Block> exact_blocks;
    if (!made_first) {
      try {
        exact_blocks = carve_stages(solid, any_pinned ? &pinned_only : nullptr, input, options, exact);
      } catch (const AlgorithmError& e) {
        // the blocks within the tolerance are kept (part.off in its input
        // frame within the fallback: the repaired solid has a corner no exact
        // box covers once grow refines it, see the exact branch above)
        usable = false;
        if (progress)
          progress->info(std::string(any_pinned ? "the decomposition with the features' allowances only"
                                                : "the exact decomposition") +
                         " failed (" + e.what() + "): the blocks within the tolerance are kept");
      }
    }
    if (any_pinned && usable) {
      MillToleranceResult milled = mill_stage(solid, std::move(exact_blocks), options, exact);
      usable = milled.num_failed() == 0;
      exact_blocks = std::move(milled.blocks);
      exact_filled = std::move(milled.filled);
      exact.deviation_bound = milled.max_deviation;
    }
    if (usable && !made_first) merge_stage(std::move(exact_blocks), exact_filled, options, exact);
    if (progress && usable)
      progress->info(std::string(any_pinned ? "decomposition with the features' allowances only: "
                                            : "exact decomposition: ") +
                     std::to_string(exact.blocks.size()) + " blocks, within the tolerance: " +
                     std::to_string(result.blocks.size()));
    DecomposeTimings& t = exact.timings;
    const DecomposeTimings& a = result.timings;
    const DecomposeTimings& b = base.timings;
    if (made_first) {
      t = a;
    } else {
      add_stage_times(t, a, b);
      t.tolerance += a.tolerance - b.tolerance;
    }
    if (usable && exact.blocks.size() <= result.blocks.size()) {
      exact.num_allowed_faces = result.num_allowed_faces;
      exact.num_floored_faces = result.num_floored_faces;
      exact.num_tolerance_rounds = result.num_tolerance_rounds;
      result = std::move(exact);
      filled = std::move(exact_filled);
    } else {
      result.timings = t;
    }
  }
  // The overhang ladder (issue 17): uniform angles where the blocks leave
  // the tolerance room.
  if (result.tolerance > 0 && options.max_overhang_deg == 0 && !options.tolerance_overhang_ladder_deg.empty() &&
      result.blocks.size() > 1 && result.deviation_bound <= options.tolerance_ladder_slack * result.tolerance)
    overhang_ladder_stage(solid, pinned, input, options, base, result, filled);
  // A block made by a merge below must survive the export: rounded to the
  // input frame (finalize_blocks()) and written in single precision (its
  // machine STL).
  FinalizeOptions fo;
  fo.normal_tolerance = height_field_normal_tolerance(result.max_overhang_deg);
  const Mesh& decomposed = result.repaired_input ? *result.repaired_input : input;
  const RoundedBlockCheck rounding(decomposed, result, fo);
  const double decomposed_diagonal = bounding_box(decomposed).diagonal();
  const auto export_defect = [&rounding, &result, &fo, decomposed_diagonal](const Block& b) {
    Mesh finished;
    std::string defect = rounding.defect(b, &finished);
    if (defect.empty() && !finished.faces.empty()) {
      // the export's own float32 step (export_decomposition())
      Mesh stl = machine_mesh_of(finished, b.axis, result.rotation);
      const Eigen::Matrix3d to_machine = axis_to_machine(b.axis) * result.rotation;
      const Vec3 direction = detail::rotate_accurately(result.rotation.transpose(), axis_direction(b.axis));
      if (!detail::clean_block_for_stl(stl, finished, to_machine, direction, decomposed_diagonal, fo).ok)
        defect = "not a solid in single precision";
    }
    return defect;
  };
  // 8. fewer blocks within the tolerance (issue 17): merges into milled shapes
  if (result.tolerance > 0) {
    const auto tt = Clock::now();
    ToleranceMergeOptions to;
    to.tolerance = result.tolerance;
    to.max_height = result.max_height;
    to.machine_size = machine;
    to.progress = progress;
    if (!filled.empty()) to.filled = &filled;
    to.block_defect = export_defect;
    ToleranceMergeResult merged = merge_within_tolerance(solid, std::move(result.blocks), to);
    result.blocks = std::move(merged.blocks);
    result.filled = std::move(merged.filled);
    result.deviation_bound = std::max(result.deviation_bound, merged.max_deviation);
    result.num_tolerance_merges = merged.num_merges;
    result.timings.tolerance += seconds_since(tt);
    if (progress)
      progress->info(std::to_string(merged.num_merges) + " merges within the tolerance (" +
                     std::to_string(merged.num_candidates) + " milled shapes evaluated)");
  }
  // 9. no slivers (issue 17): blocks thinner than sliver_threshold()
  //    where the model is thicker are merged or dropped within the
  //    tolerance; at T = 0 only counted (remove_slivers.h).
  // the sliver stage's options within tolerance t (validate's threshold
  // sliver_threshold(): max(1e-4 x diagonal, min(t, H / 4))); shared by steps 9 and 9b
  const auto sliver_options = [&](double t) {
    SliverRemovalOptions so;
    so.min_thickness = sliver_threshold(options.sliver_thickness * diagonal, t, result.max_height);
    so.tolerance = t;
    so.max_height = result.max_height;
    so.machine_size = machine;
    so.progress = progress;
    so.block_defect = export_defect;
    return so;
  };
  {
    const auto tt = Clock::now();
    SliverRemovalOptions so = sliver_options(result.tolerance);
    if (!result.filled.empty()) so.filled = &result.filled;
    so.thicken = false;  // after step 9c's re-decompositions, which may save a block
    if (so.min_thickness > 0) {
      SliverRemovalResult sl = remove_slivers(solid, std::move(result.blocks), so);
      result.blocks = std::move(sl.blocks);
      if (result.tolerance > 0) result.filled = std::move(sl.filled);
      result.deviation_bound = std::max(result.deviation_bound, sl.max_deviation);
      result.sliver_thickness = so.min_thickness;
      result.num_slivers = sl.num_left;
      result.num_slivers_merged = sl.num_merged;
      result.num_slivers_dropped = sl.num_dropped;
      // 9c. a sliver left: decomposed again together with a neighbour,
      //     exactly (nothing deviates: at T = 0 too); then thickened with
      //     the material beyond a cut face (remove_slivers.h, 4.; exact);
      //     last, decomposed again into one block more
      if (sl.num_left > 0) {
        std::size_t gone = recarve_slivers(solid, input, options, result, result.filled, so.min_thickness,
                                           export_defect, /*last_resort=*/false);
        if (result.num_slivers > gone) {
          so.thicken = true;
          so.filled = result.filled.empty() ? nullptr : &result.filled;
          SliverRemovalResult th = thicken_slivers(solid, std::move(result.blocks), so);
          result.blocks = std::move(th.blocks);
          if (!th.filled.empty()) result.filled = std::move(th.filled);
          result.deviation_bound = std::max(result.deviation_bound, th.max_deviation);
          result.num_slivers_thickened = th.num_thickened;
          gone += th.num_thickened;
          if (th.num_left > 0)
            gone += recarve_slivers(solid, input, options, result, result.filled, so.min_thickness, export_defect,
                                    /*last_resort=*/true);
        }
        result.num_slivers -= std::min(result.num_slivers, gone);
        result.num_slivers_recarved = gone - result.num_slivers_thickened;
      }
    }
    (result.tolerance > 0 ? result.timings.tolerance : result.timings.carve) += seconds_since(tt);
  }
  // 9b. at the command's default, slivers left at T = 0: the same blocks
  //     with the sliver stage run again within a tolerance: 1, then 2,
  //     then 5 x the sliver thickness (1e-4 x diagonal), up to the fallback
  //     tolerance, each level on what the one before left (only the slivers
  //     it could not remove, and those the larger threshold adds, are
  //     treated again: the threshold is max(1e-4 x diagonal, T), a larger T
  //     makes more blocks slivers), until none is left; decompose() chooses.
  if (slivers_within && result.tolerance == 0 && result.num_slivers > 0 && options.fallback_tolerance_fraction > 0) {
    const auto tt = Clock::now();
    std::vector<double> ladder;
    for (double f : {options.sliver_thickness, 2 * options.sliver_thickness, options.fallback_tolerance_fraction})
      if (f > 0 && f <= options.fallback_tolerance_fraction && (ladder.empty() || f > ladder.back())) ladder.push_back(f);
    std::vector<Block> current = result.blocks;
    std::vector<char> current_filled;  // empty: no block sticks out (exact blocks)
    double bound = 0.0;
    std::size_t merged = 0, dropped = 0, thickened = result.num_slivers_thickened, slivers = result.num_slivers;
    for (double f : ladder) {
      const double tolerance = f * diagonal;
      SliverRemovalOptions so = sliver_options(tolerance);
      if (!current_filled.empty()) so.filled = &current_filled;
      if (progress)
        progress->info(f == ladder.front()
                           ? std::to_string(slivers) + " sliver block(s) at tolerance 0: the sliver stage again on "
                                                       "the exact blocks, within " + std::to_string(f) + " x diagonal"
                           : std::to_string(slivers) + " sliver block(s) left: the sliver stage again on those "
                                                       "blocks, within " + std::to_string(f) + " x diagonal");
      SliverRemovalResult sl = remove_slivers(solid, std::move(current), so);
      bound = std::max(bound, sl.max_deviation);
      merged += sl.num_merged;
      dropped += sl.num_dropped;
      thickened += sl.num_thickened;
      slivers = sl.num_left;
      current = std::move(sl.blocks);
      if (!sl.filled.empty()) current_filled = std::move(sl.filled);
      if (slivers > 0) continue;
      DecomposeResult within = result;
      within.tolerance = tolerance;
      within.blocks = std::move(current);
      within.filled = current_filled.empty() ? std::vector<char>(within.blocks.size(), 0) : std::move(current_filled);
      within.deviation_bound = bound;
      within.sliver_thickness = so.min_thickness;
      within.num_slivers = 0;
      within.num_slivers_merged = merged;
      within.num_slivers_dropped = dropped;
      within.num_slivers_thickened = thickened;
      within.timings.tolerance += seconds_since(tt);
      *slivers_within = std::move(within);
      break;
    }
    result.timings.carve += seconds_since(tt);
  }
  result.timings.total = seconds_since(start);
  if (slivers_within && *slivers_within) (*slivers_within)->timings.total = result.timings.total;
  return result;
}

}  // namespace

std::size_t fallback_carve_limit(std::size_t exact_carved, double min_gain) {
  if (!(min_gain > 0) || exact_carved == 0) return 0;
  return static_cast<std::size_t>(std::ceil((1.0 - min_gain) * static_cast<double>(exact_carved)));
}

DecomposeResult decompose(const Mesh& input, const DecomposeOptions& options) {
  check_options(options);
  // RepairGaveUp is thrown at tolerance 0 only, and only when options.repair
  if (!(options.fallback_tolerance_fraction > 0)) return decompose_once(input, options);
  const auto start = Clock::now();
  DecomposeOptions within = options;
  within.tolerance_fraction = options.fallback_tolerance_fraction;
  within.tolerance_abs = std::numeric_limits<double>::infinity();
  // the exact blocks are known to fail here (repair given up, or slivers):
  // a round is never given up for carving more blocks than they have
  within.tolerance_exact_margin = -1;
  within.tolerance_overhang_ladder_deg.clear();  // the fallback pays for no extra carves
  const std::string instead = "Decomposing within a tolerance of " + std::to_string(options.fallback_tolerance_fraction) +
                              " x the bounding-box diagonal instead";
  DecomposeResult exact;
  std::optional<DecomposeResult> slivers_within;  // the exact blocks with the slivers removed within the fallback
  try {
    exact = decompose_once(input, options, &slivers_within);
  } catch (const RepairGaveUp& e) {
    if (options.progress)
      options.progress->warn(std::string(e.what()) + "\n" + instead +
                             " (creases and spikes finer than it may keep "
                             "their undercuts; every block is still an exact height field, the deviation is "
                             "measured). Give --tolerance 0 to refuse, or --tolerance F to choose it.");
    DecomposeResult result = decompose_once(input, within);
    result.tolerance_fallback = e.what();
    result.timings.total = seconds_since(start);
    return result;
  }
  if (exact.tolerance > 0 || exact.num_slivers == 0) return exact;
  // Slivers at tolerance 0 (issue 17, "no slivers"): a slab thinner than
  // 1e-4 x diagonal cannot be milled or glued; nothing may deviate at
  // tolerance 0, so the sliver stage only counted them. At the default they
  // are left to the fallback tolerance, two ways: (a) the whole model
  // decomposed again within it (its sliver stage drops or merges them within
  // it; usually fewer blocks), (b) the exact blocks with the sliver stage run
  // again within it (decompose_once(): only the slivers change). The one of
  // those without slivers with fewer blocks is kept ((b) on a tie: it
  // deviates only where the slivers were); when both have slivers, the
  // exact blocks.
  const std::string why = std::to_string(exact.num_slivers) + " block(s) of the exact decomposition thinner than " +
                          std::to_string(exact.sliver_thickness) +
                          " model units (1e-4 x diagonal) where the model is thicker (slivers)";
  if (options.progress)
    options.progress->warn(why + "\n" + instead +
                           " (slivers dropped or merged within it; every block is still an exact height field, the "
                           "deviation is measured). Give --tolerance 0 to keep the exact blocks.");
  std::optional<DecomposeResult> chosen;
  if (slivers_within && slivers_within->num_slivers == 0) chosen = std::move(*slivers_within);
  const std::size_t in_place_blocks = chosen ? chosen->blocks.size() : 0;
  // When the in-place removal already left no sliver, the whole
  // re-decomposition only pays when its allowances change the carve: it is
  // given up after a round that carves at least (1 - fallback_min_carve_gain)
  // x the exact carve's blocks (a count, deterministic; decompose.h).
  const std::size_t carve_limit =
      chosen ? fallback_carve_limit(exact.num_carved_blocks, options.fallback_min_carve_gain) : 0;
  try {
    DecomposeResult result = decompose_once(input, within, nullptr, carve_limit);
    if (result.num_slivers == 0 && (!chosen || result.blocks.size() < chosen->blocks.size())) {
      chosen = std::move(result);
    } else if (options.progress) {
      options.progress->warn(
          result.num_slivers > 0
              ? "within the fallback tolerance " + std::to_string(result.num_slivers) + " sliver block(s) are left too"
              : "within the fallback tolerance " + std::to_string(result.blocks.size()) + " blocks, not fewer");
    }
  } catch (const FallbackGivenUp& e) {
    if (options.progress)
      options.progress->warn(std::string("the decomposition within the fallback tolerance was given up (") + e.what() +
                             ", less than " + std::to_string(std::lround(options.fallback_min_carve_gain * 100)) +
                             "% below the exact carve's " + std::to_string(exact.num_carved_blocks) +
                             " blocks: too few to pay for milling, measuring and merging them); the in-place "
                             "blocks are kept");
  } catch (const AlgorithmError& e) {
    if (options.progress)
      options.progress->warn(std::string("the decomposition within the fallback tolerance failed (") + e.what() + ")");
  }
  if (chosen) {
    if (options.progress && in_place_blocks > 0 && in_place_blocks == chosen->blocks.size())
      options.progress->warn("the exact blocks are kept, their slivers removed within the fallback tolerance (" +
                             std::to_string(chosen->num_slivers_dropped) + " dropped, " +
                             std::to_string(chosen->num_slivers_merged) + " merged, " +
                             std::to_string(chosen->num_slivers_thickened) + " thickened)");
    chosen->tolerance_fallback = why;
    chosen->timings.total = seconds_since(start);
    return std::move(*chosen);
  }
  if (options.progress)
    options.progress->warn("slivers are left within the fallback tolerance both ways: the exact decomposition is kept");
  exact.timings.total = seconds_since(start);
  return exact;
}

}  // namespace subfab
