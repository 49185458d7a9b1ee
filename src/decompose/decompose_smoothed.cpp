// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/decompose_smoothed.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "decompose/block_pairs_detail.h"
#include "geometry/hausdorff_distance.h"
#include "geometry/rotate_accurately.h"
#include "geometry/surface_deviation.h"
#include "subfab/checks/require_closed_solid.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/carve_blocks.h"
#include "subfab/decompose/finalize_blocks.h"
#include "subfab/decompose/merge_blocks.h"
#include "subfab/decompose/orient_mesh.h"
#include "subfab/fidelity/find_infeasible_features.h"
#include "subfab/geometry/coordinate_rounding.h"
#include "subfab/validate/validate_decomposition.h"

namespace subfab {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void check_options(const SmoothedDecomposeOptions& o) {
  if (o.decompose.max_overhang_deg != 0)
    throw InvalidArgumentError("--smooth makes exact height-field blocks: it cannot be combined with --max-overhang");
  if (o.max_carve_rounds < 1) throw InvalidArgumentError("decompose_smoothed: max_carve_rounds must be >= 1");
  if (!(o.hausdorff_error > 0) || !std::isfinite(o.hausdorff_error))
    throw InvalidArgumentError("decompose_smoothed: the Hausdorff error bound must be a positive fraction");
}

//! The boxes grown by `margin` on every side but the base (its -axis side),
//! side by side, where the added slab meets no later box in carve order (no
//! later block loses material, so none gets a new face) and the box still
//! fits the limits: the room the restoration may put details back in (the
//! boxes were shrunk to the smoothed surface, 4.3.4).
std::vector<HeightBox> room_boxes(const std::vector<HeightBox>& boxes, double margin, double max_height,
                                  const Vec3& machine) {
  std::vector<HeightBox> out = boxes;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const int k = axis_dimension(boxes[i].axis);
    for (int dim = 0; dim < 3; ++dim)
      for (const bool upper : {false, true}) {
        if (dim == k && upper != (axis_sign(boxes[i].axis) > 0)) continue;  // the base side
        Box3 grown = out[i].box, slab = out[i].box;
        if (upper) {
          grown.max[dim] += margin;
          slab.min[dim] = out[i].box.max[dim];
          slab.max[dim] = grown.max[dim];
        } else {
          grown.min[dim] -= margin;
          slab.max[dim] = out[i].box.min[dim];
          slab.min[dim] = grown.min[dim];
        }
        if (!box_fits_limits(grown, boxes[i].axis, max_height, machine)) continue;
        bool free = true;
        for (std::size_t j = i + 1; j < boxes.size() && free; ++j) free = !slab.overlaps(boxes[j].box);
        if (free) out[i].box = grown;
      }
  }
  return out;
}

//! Faces of `solid` with a point (corners, edge midpoints, centroid) farther
//! than `tolerance` from every block surface: the restored surface must lie
//! on the blocks (it leaves the union of the boxes otherwise).
std::vector<int> uncovered_faces(const Mesh& solid, const std::vector<Block>& blocks, double tolerance) {
  Mesh all;
  for (const Block& b : blocks) {
    const int offset = static_cast<int>(all.vertices.size());
    all.vertices.insert(all.vertices.end(), b.mesh.vertices.begin(), b.mesh.vertices.end());
    for (const Triangle& t : b.mesh.faces) all.faces.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  std::vector<char> bad(solid.faces.size(), 0);
  if (all.faces.empty()) {
    std::fill(bad.begin(), bad.end(), 1);
  } else {
    const detail::SurfaceDistance distance(all);
    parallel_for(0, solid.faces.size(), [&](std::size_t f) {
      const Triangle& t = solid.faces[f];
      const Vec3& a = solid.vertices[static_cast<std::size_t>(t[0])];
      const Vec3& b = solid.vertices[static_cast<std::size_t>(t[1])];
      const Vec3& c = solid.vertices[static_cast<std::size_t>(t[2])];
      for (const Vec3& p : {a, b, c, Vec3((a + b) / 2), Vec3((b + c) / 2), Vec3((c + a) / 2), Vec3((a + b + c) / 3)})
        if (distance(p) > tolerance) {
          bad[f] = 1;
          return;
        }
    });
  }
  std::vector<int> out;
  for (std::size_t f = 0; f < bad.size(); ++f)
    if (bad[f]) out.push_back(static_cast<int>(f));
  return out;
}

//! Vertices to hold at their smoothed positions after a failed carve: the
//! corners of the uncovered faces, and for each failing block the corners of
//! the restored faces near it that face away from its axis (all the moved
//! vertices near it when there are none).
std::vector<int> vertices_to_hold(const Mesh& restored, const Mesh& smoothed, const std::vector<Block>& blocks,
                                  const std::vector<std::size_t>& failed, const std::vector<int>& uncovered) {
  std::vector<int> out;
  for (int f : uncovered)
    for (int v : restored.faces[static_cast<std::size_t>(f)]) out.push_back(v);
  for (std::size_t b : failed) {
    const Block& block = blocks[b];
    BoundingBox box = bounding_box(block.mesh);
    const double pad = 1e-9 * std::max(1.0, box.diagonal());
    box.min.array() -= pad;
    box.max.array() += pad;
    const Vec3 d = axis_direction(block.axis);
    std::vector<int> near, away;
    for (std::size_t f = 0; f < restored.faces.size(); ++f) {
      BoundingBox fb;
      for (int v : restored.faces[f]) fb.extend(restored.vertices[static_cast<std::size_t>(v)]);
      if (!detail::boxes_touch(fb, box)) continue;
      for (int v : restored.faces[f]) near.push_back(v);
      if (face_normal_scaled(restored, f).dot(d) < 0)
        for (int v : restored.faces[f]) away.push_back(v);
    }
    const auto moved = [&](int v) {
      return restored.vertices[static_cast<std::size_t>(v)] != smoothed.vertices[static_cast<std::size_t>(v)];
    };
    const bool any_away = std::any_of(away.begin(), away.end(), moved);
    for (int v : any_away ? away : near) out.push_back(v);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

//! Area-weighted mean distance of `modified`'s surface to `input`'s over the
//! whole surface (its faces not in `input` measured, the rest at 0), and
//! into `hausdorff` the symmetric Hausdorff distance of those faces, within
//! `error` (model units).
double whole_surface_mean(const Mesh& input, const Mesh& modified, double error, double* hausdorff) {
  const std::vector<int> changed = detail::faces_not_in(modified, input);
  if (changed.empty()) return 0.0;
  const detail::SurfaceDeviation d = detail::surface_deviation(input, input, modified, changed, error);
  if (hausdorff) *hausdorff = d.hausdorff;
  double changed_area = 0;
  for (int f : changed) changed_area += face_area(modified, static_cast<std::size_t>(f));
  const double area = surface_area(modified);
  return area > 0 ? d.mean * changed_area / area : 0.0;
}

//! decompose() of the smoothed model. Where it fails and the input itself
//! has no feature a height-field block cannot cover (in the frame
//! decompose() would choose for it), the smoothing made the trouble: on a
//! CAD part it rounds sharp edges and tilts flat faces off the axes (a part
//! decomposed exactly in 2 blocks failed after 40 s of repair). The error
//! then says so and what to do instead.
DecomposeResult decompose_the_smoothed(const Mesh& input, const Mesh& smoothed, const DecomposeOptions& d) {
  try {
    return decompose(smoothed, d);
  } catch (const AlgorithmError& e) {
    bool input_feasible = false;
    try {
      OrientOptions o;
      const double diagonal = bounding_box(input).diagonal();
      if (diagonal > 0)
        o.precision_snap_tolerance = std::min(4 * coordinate_rounding(input) / diagonal, d.max_precision_snap);
      input_feasible = d.orient ? orient_mesh(input, o).infeasible.feasible() : find_infeasible_features(input).feasible();
    } catch (const std::exception&) {
      input_feasible = false;  // unknown: the original error stands alone
    }
    if (!input_feasible) throw;
    std::string what = e.what();
    while (!what.empty() && what.back() == '.') what.pop_back();
    throw AlgorithmError(std::string("the smoothing made features no height-field block can cover: the input itself has "
                                     "none in ") +
                         (d.orient ? "the frame decompose would choose for it" : "its own frame") +
                         ", the smoothed model fails (it rounds sharp edges and tilts flat faces off the axes, as on "
                         "a CAD part). --smooth is meant for scanned and sculpted models: decompose this one without "
                         "--smooth (exact blocks), or with --tolerance F alone. What failed on the smoothed model: " +
                         what);
  }
}

//! `--smooth` with `--tolerance`: the smoothed model decomposed within the
//! tolerance (the allowances of decompose(), issue 17); no restoration (the
//! blocks' milled shapes are measured against the smoothed model). The
//! deviations add up (triangle inequality of the Hausdorff distance): the
//! blocks lie within the smoothing's largest vertex move plus the measured
//! deviation bound of the input. Slivers are judged at T, as decompose()
//! judges them within T (the smoothing makes no pieces).
SmoothedDecomposeResult decompose_smoothed_within(const Mesh& input, SmoothResult smoothed, DecomposeOptions d,
                                                  double tolerance, SmoothedDecomposeResult out) {
  SmoothedDecomposeReport& report = out.report;
  Progress* progress = d.progress;
  // each smoothed point lies within its vertices' largest move of the same
  // barycentric point of the input face: a bound of the Hausdorff distance
  const double smoothing = report.smooth.max_displacement;
  d.tolerance_fraction = 1.0;  // the tolerance in model units (of the input's diagonal)
  d.tolerance_abs = tolerance;
  d.fallback_tolerance_fraction = 0.0;
  DecomposeResult result = decompose_the_smoothed(input, smoothed.mesh, d);
  report.within_tolerance = true;
  report.tolerance = tolerance;
  report.num_blocks_smoothed = report.num_blocks = result.blocks.size();
  // what the blocks decompose: the smoothed model (snapped within its file's
  // rounding when decompose() had to)
  report.decomposed_deviation = smoothing + (result.repaired_input ? result.repair.max_deviation : 0.0);
  if (!result.repaired_input) result.repaired_input = smoothed.mesh;
  report.max_deviation = report.decomposed_deviation + result.deviation_bound;
  report.deviation_error = 0.0;  // a bound, not a measure
  report.smoothed_mean_deviation =
      whole_surface_mean(input, smoothed.mesh, std::max(report.smooth.hausdorff_error, 1e-300), nullptr);
  report.mean_deviation = report.smoothed_mean_deviation;
  result.timings.total += report.smooth.seconds;
  if (progress) {
    std::ostringstream msg;
    msg << "smoothed (vertices moved at most " << report.fraction(smoothing)
        << " x diagonal) and decomposed within " << report.fraction(tolerance) << " x diagonal: "
        << report.num_blocks << " blocks; deviation of the blocks from the input at most "
        << report.fraction(report.max_deviation) << " x diagonal (smoothing " << report.fraction(smoothing)
        << " + tolerance's measured bound " << report.fraction(result.deviation_bound) << ")";
    progress->info(msg.str());
  }
  out.decomposition = std::move(result);
  out.smoothed = std::move(smoothed.mesh);
  return out;
}

}  // namespace

SmoothedDecomposeResult decompose_smoothed(const Mesh& input_mesh, const SmoothedDecomposeOptions& options) {
  check_options(options);
  Progress* progress = options.decompose.progress;
  SmoothedDecomposeResult out;
  SmoothedDecomposeReport& report = out.report;

  // 1. smooth (4.3.5, first step)
  SmoothOptions so = options.smooth;
  so.progress = progress;
  SmoothResult smoothed = smooth_for_decomposition(input_mesh, so);  // InvalidMeshError: not a solid
  report.smooth = smoothed.report;
  report.bbox_diagonal = smoothed.report.bbox_diagonal;
  Mesh input = input_mesh;
  require_closed_solid(input);  // the same (possibly flipped) solid the smoothing worked on

  // The limits in model units of the INPUT's diagonal (the smoothed model's
  // is a little shorter).
  const double input_diagonal = report.bbox_diagonal;
  DecomposeOptions d = options.decompose;
  d.max_height_abs = std::min(d.max_height_abs, d.max_height_fraction * input_diagonal);
  d.max_height_fraction = std::numeric_limits<double>::infinity();
  const double tolerance = std::min(d.tolerance_fraction * input_diagonal, d.tolerance_abs);
  if (tolerance > 0) return decompose_smoothed_within(input, std::move(smoothed), d, tolerance, std::move(out));

  // 2. decompose the smoothed model
  DecomposeResult result = decompose_the_smoothed(input, smoothed.mesh, d);
  if (result.repaired_input)
    throw AlgorithmError("the smoothed model (cap " + std::to_string(options.smooth.max_deviation) +
                         " x diagonal) still has " + std::to_string(result.repair.num_features) +
                         " feature(s) no height-field block can cover in the chosen frame; smooth it more (a larger "
                         "--smooth cap) or decompose without --smooth (the local repair handles them then)");
  report.num_blocks_smoothed = result.blocks.size();
  const auto start = Clock::now();
  StageScope stage(progress, "restore");

  // 3.-4. restore, carve again, check
  const std::size_t n = input.num_vertices();
  Mesh smoothed_c;  // the smoothed model in the canonical frame, the input's connectivity
  smoothed_c.vertices.assign(result.canonical.vertices.begin(),
                             result.canonical.vertices.begin() + static_cast<std::ptrdiff_t>(n));
  smoothed_c.faces = input.faces;
  const Mesh original_c = rotate_into_frame(input, result.rotation, result.frame_snap_tolerance);
  const Vec3 machine = options.decompose.machine ? *options.decompose.machine
                                                 : Vec3::Constant(std::numeric_limits<double>::infinity());
  const double diagonal = bounding_box(original_c).diagonal();
  // Room for the details: the boxes grown by the smoothing's largest move.
  std::vector<HeightBox> room =
      room_boxes(result.ordered_boxes, report.smooth.max_displacement * (1 + 1e-6), result.max_height, machine);
  // The restored solid in input coordinates (what the blocks decompose).
  const Eigen::Matrix3d back = result.rotation.transpose();
  const auto in_input_frame = [&](const Mesh& restored_c) {
    Mesh m;
    m.faces = input.faces;
    m.vertices.reserve(n);
    for (std::size_t v = 0; v < n; ++v)
      m.vertices.push_back(restored_c.vertices[v] == original_c.vertices[v]
                               ? input.vertices[v]
                               : detail::rotate_accurately(back, restored_c.vertices[v]));
    return m;
  };
  std::vector<int> held;
  bool room_taken_back = false;
  RestoreDetailsResult restored;
  std::vector<Block> blocks;
  for (int round = 0;; ++round) {
    RestoreDetailsOptions ro = options.restore;
    ro.held = held.empty() ? nullptr : &held;
    ro.progress = progress;
    ro.room = &room;
    restored = restore_details(original_c, smoothed_c, result.ordered_boxes, ro);
    ++report.num_carve_rounds;
    CarveOptions co;
    co.max_height = result.max_height;
    co.machine_size = machine;
    co.progress = progress;
    blocks = carve_blocks(restored.mesh, room, co).blocks;
    std::vector<std::size_t> failed;
    for (std::size_t b = 0; b < blocks.size(); ++b)
      if (!is_height_field(blocks[b].mesh, axis_direction(blocks[b].axis))) failed.push_back(b);
    // The export's check (finalize_blocks(): rounded to the input frame,
    // cleaned, closed, no self-intersection) on the blocks that pass: a block
    // of the restored surface can cross itself once rounded (max planck).
    {
      DecomposeResult rounded;
      rounded.rotation = result.rotation;
      rounded.canonical = restored.mesh;
      rounded.num_input_vertices = n;
      rounded.blocks = blocks;
      const std::vector<std::string> defects = block_defects_after_rounding(in_input_frame(restored.mesh), rounded);
      for (std::size_t b = 0; b < blocks.size(); ++b)
        if (!defects[b].empty() && std::find(failed.begin(), failed.end(), b) == failed.end()) {
          failed.push_back(b);
          ++report.num_rounding_failures;
          if (progress) progress->info("block " + std::to_string(b + 1) + " after rounding: " + defects[b]);
        }
      std::sort(failed.begin(), failed.end());
    }
    const std::vector<int> uncovered = uncovered_faces(restored.mesh, blocks, 1e-9 * diagonal);
    report.num_failed_blocks += failed.size();
    report.num_uncovered_faces += uncovered.size();
    if (failed.empty() && uncovered.empty()) break;
    std::vector<int> more = vertices_to_hold(restored.mesh, smoothed_c, blocks, failed, uncovered);
    if (round + 1 >= options.max_carve_rounds) {  // hold everything near the failures
      for (std::size_t v = 0; v < n; ++v)
        if (restored.mesh.vertices[v] != smoothed_c.vertices[v]) {
          const Vec3& p = restored.mesh.vertices[v];
          for (std::size_t b : failed) {
            const BoundingBox box = bounding_box(blocks[b].mesh);
            if ((p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all())
              more.push_back(static_cast<int>(v));
          }
        }
    }
    const std::size_t before = held.size();
    held.insert(held.end(), more.begin(), more.end());
    std::sort(held.begin(), held.end());
    held.erase(std::unique(held.begin(), held.end()), held.end());
    if (progress)
      progress->info(std::to_string(failed.size()) + " block(s) of the restored solid failed the checks and " +
                     std::to_string(uncovered.size()) + " restored face(s) are not on the blocks; holding " +
                     std::to_string(held.size() - before) + " more vertices at their smoothed positions");
    if (held.size() == before && !room_taken_back) {  // the grown boxes may be what fails: carve with the boxes
      room = result.ordered_boxes;
      room_taken_back = true;
      if (progress) progress->info("carving with the boxes as the smoothed model's decomposition left them");
      continue;
    }
    if (held.size() == before)
      throw AlgorithmError("restoring the details: " + std::to_string(failed.size()) + " block(s) fail and " +
                           std::to_string(uncovered.size()) +
                           " face(s) are not covered with every vertex near them at its smoothed position "
                           "(internal error; please report it with the input)");
  }
  report.restore = restored.report;
  report.num_held = held.size();

  // 5. merge (4.3.4 post-processing)
  {
    MergeOptions mo;
    mo.max_height = result.max_height;
    mo.machine_size = machine;
    mo.progress = progress;
    if (options.decompose.merge) {
      MergeResult merged = merge_blocks(std::move(blocks), mo);
      result.num_merges = merged.num_merges;
      blocks = std::move(merged.blocks);
    }
  }
  report.num_blocks = blocks.size();

  Mesh restored_input = in_input_frame(restored.mesh);
  require_closed_solid_result(restored_input, "the restored solid is not a valid solid in the input frame: ",
                              "; internal error, please report it with the input");

  // 6. deviation of the blocks' union (the restored solid) from the input
  report.deviation_error = options.hausdorff_error * report.bbox_diagonal;
  const double error = std::max(report.deviation_error, 1e-300);
  report.mean_deviation = whole_surface_mean(input, restored_input, error, &report.max_deviation);
  report.smoothed_mean_deviation = whole_surface_mean(input, smoothed.mesh, error, nullptr);

  result.blocks = std::move(blocks);
  result.ordered_boxes = room;
  result.canonical = restored.mesh;
  result.num_input_vertices = n;
  result.repaired_input = std::move(restored_input);
  report.restore_seconds = seconds_since(start);
  result.timings.total += report.restore_seconds + report.smooth.seconds;
  if (progress) {
    std::ostringstream msg;
    msg << "smoothed (cap " << options.smooth.max_deviation << " x diagonal): " << report.num_blocks_smoothed
        << " blocks; details restored: " << report.num_blocks << " blocks; deviation of the blocks from the input: "
        << "Hausdorff " << report.max_deviation << " (" << report.fraction(report.max_deviation)
        << " x diagonal), mean " << report.mean_deviation << " (" << report.fraction(report.mean_deviation)
        << "; smoothed model: Hausdorff " << report.fraction(report.smooth.hausdorff) << ", mean "
        << report.fraction(report.smoothed_mean_deviation) << ")";
    progress->info(msg.str());
  }
  out.decomposition = std::move(result);
  out.smoothed = std::move(smoothed.mesh);
  return out;
}

}  // namespace subfab
