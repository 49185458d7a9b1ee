// SPDX-License-Identifier: GPL-3.0-or-later
// The checks of a decomposition that need no CGAL (1, 2, 6, 7) and the
// driver of all seven; the exact booleans and the coverage distances are in
// validate_booleans.cpp.
#include "subfab/validate/validate_decomposition.h"
#include "validate/box_separation.h"
#include "validate/validate_booleans.h"
#include "subfab/validate/block_name.h"
#include "subfab/validate/check_single_precision.h"
#include "subfab/validate/match_frame_blocks.h"
#include "subfab/validate/fill_deviation_upper_bound.h"
#include "subfab/validate/measure_fill_deviation.h"

#include <algorithm>
#include <chrono>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>

#include "subfab/checks/check_self_intersections.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/geometry/axis.h"

namespace subfab {
namespace {

std::string fmt(const char* format, double a, double b = 0.0, double c = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b, c);
  return buf;
}

void add_failure(CheckReport& report, std::string line) {
  report.passed = false;
  ++report.num_failures;
  if (report.failures.size() < 20) report.failures.push_back(std::move(line));
}

CheckReport named_check(std::string name) {
  CheckReport r;
  r.name = std::move(name);
  return r;
}

//! Extent [min, max] of u.v over the vertices of `mesh`.
std::pair<double, double> extent_along(const Mesh& mesh, const Vec3& u) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Vec3& v : mesh.vertices) {
    const double h = u.dot(v);
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  return {lo, hi};
}

}  // namespace

std::string block_name(std::size_t i) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "block %03zu", i);
  return buf;
}

double overlap_volume_bound(const Mesh& a, const Mesh& b, const Eigen::Matrix3d& frame) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (a.vertices.empty() || b.vertices.empty()) return 0.0;
  if ((frame.transpose() * frame - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9) return kInf;
  const double det = std::abs(frame.determinant());
  // largest |coordinate|, for the rounding margin of the dot products
  const double largest = std::max(largest_coordinate(a), largest_coordinate(b));
  double bound = 1.0;
  for (int k = 0; k < 3; ++k) {
    const Vec3 u = frame.row(k).transpose();
    // |fl(u.v) - u.v| <= 3.4e-16 sum |u_i||v_i|: widen every interval by more than that.
    const double margin = 4e-16 * u.cwiseAbs().sum() * largest;
    const auto [a_lo, a_hi] = extent_along(a, u);
    const auto [b_lo, b_hi] = extent_along(b, u);
    const double width = (std::min(a_hi, b_hi) + margin) - (std::max(a_lo, b_lo) - margin);
    if (width <= 0.0) return 0.0;
    bound *= width * (1.0 + 1e-15);
  }
  return bound / (det * (1.0 - 1e-12));
}

SolidReport check_closed_solid(const Mesh& block) {
  SolidReport r;
  r.num_faces = block.num_faces();
  // Directed edge -> count.
  std::map<std::pair<int, int>, int> directed;
  for (const Triangle& t : block.faces)
    for (int k = 0; k < 3; ++k) ++directed[{t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]}];
  for (const auto& [e, count] : directed) {
    if (count > 1) {
      ++r.num_non_manifold_edges;
      continue;
    }
    if (directed.find({e.second, e.first}) == directed.end()) ++r.num_boundary_edges;
  }
  // Vertex fans: the faces around a vertex must form one cycle through edges.
  std::vector<std::vector<std::pair<int, int>>> link(block.num_vertices());  // (next, prev) corners
  for (const Triangle& t : block.faces)
    for (int k = 0; k < 3; ++k)
      link[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])].push_back(
          {t[static_cast<std::size_t>((k + 1) % 3)], t[static_cast<std::size_t>((k + 2) % 3)]});
  for (const auto& fan : link) {
    if (fan.empty()) continue;
    // Walk next -> prev links: each face (a, b) continues with the face whose `a` equals this `b`.
    std::unordered_map<int, int> next_of;
    for (const auto& [a, b] : fan) next_of[a] = b;
    std::size_t steps = 0;
    int start = fan.front().first, cur = start;
    do {
      auto it = next_of.find(cur);
      if (it == next_of.end()) break;
      cur = it->second;
      ++steps;
    } while (cur != start && steps <= fan.size());
    if (steps != fan.size() || cur != start) ++r.num_non_manifold_vertices;
  }
  for (std::size_t f = 0; f < block.num_faces(); ++f)
    if (face_normal_scaled(block, f).squaredNorm() == 0.0) ++r.num_degenerate_faces;
  r.volume = signed_volume(block);
  return r;
}

HeightFieldReport check_height_field(const Mesh& block, const Vec3& direction, const HeightFieldOptions& options) {
  HeightFieldReport r;
  if (block.vertices.empty()) return r;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Vec3& v : block.vertices) {
    const double h = v.dot(direction);
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  r.base = lo;
  r.height = hi - lo;
  const double tol = options.plane_tolerance > 0 ? options.plane_tolerance
                                                 : 1e-9 * std::max(1.0, bounding_box(block).diagonal());
  for (std::size_t f = 0; f < block.num_faces(); ++f) {
    const Vec3 n = face_unit_normal(block, f);
    const double c = n.dot(direction);
    if (c >= 0.0 || (c >= -options.normal_tolerance && c >= r.steepest_cosine)) continue;
    bool on_base = true;
    for (int k = 0; k < 3; ++k)
      if (std::abs(block.vertices[static_cast<std::size_t>(block.faces[f][static_cast<std::size_t>(k)])].dot(direction) -
                   lo) > tol)
        on_base = false;
    if (on_base) continue;
    r.steepest_cosine = std::min(r.steepest_cosine, c);
    if (c >= -options.normal_tolerance) continue;
    ++r.num_overhang_faces;
    r.worst_cosine = std::min(r.worst_cosine, c);
  }
  return r;
}

double overhang_angle_deg(double cosine) {
  return cosine < 0.0 ? std::asin(std::min(1.0, -cosine)) * 180.0 / std::numbers::pi : 0.0;
}

double height_field_normal_tolerance(double max_overhang_deg) { return 1e-3 + overhang_sine(max_overhang_deg); }

bool is_height_field(const Mesh& block, const Vec3& direction, const HeightFieldOptions& options) {
  return check_height_field(block, direction, options).ok();
}

ValidationReport validate_decomposition(const Mesh& input, const std::vector<ValidationBlock>& blocks,
                                        const ValidationOptions& options) {
  Progress* progress = options.progress;
  const double diagonal = bounding_box(input).diagonal();
  const std::size_t n = blocks.size();
  ValidationReport report;

  // 1. closed solid
  CheckReport solid = named_check("closed oriented 2-manifold, positive volume, no self-intersection");
  std::vector<double> volumes(n, 0.0);
  {
    StageScope stage(progress, "check: closed solids");
    std::vector<SolidReport> rs(n);
    std::vector<std::size_t> crossings(n, 0);  // pairs of faces crossing (exact; the booleans need none)
    parallel_for(0, n, [&](std::size_t i) {
      rs[i] = check_closed_solid(blocks[i].mesh);
      if (rs[i].ok()) crossings[i] = check_self_intersections(blocks[i].mesh).num_offending;
    });
    std::size_t degenerate = 0;
    for (std::size_t i = 0; i < n; ++i) {
      volumes[i] = rs[i].volume;
      degenerate += rs[i].num_degenerate_faces;
      if (!rs[i].ok())
        add_failure(solid, block_name(i) + ": " + std::to_string(rs[i].num_boundary_edges) + " boundary edges, " +
                               std::to_string(rs[i].num_non_manifold_edges) + " non-manifold edges, " +
                               std::to_string(rs[i].num_non_manifold_vertices) + " non-manifold vertices, volume " +
                               fmt("%.6g", rs[i].volume));
      else if (crossings[i] > 0)
        add_failure(solid, block_name(i) + ": the surface intersects itself (" + std::to_string(crossings[i]) +
                               " pairs of faces)");
    }
    if (n == 0) add_failure(solid, "the decomposition has no blocks");
    solid.summary = std::to_string(n) + " blocks, " + std::to_string(degenerate) + " zero-area faces";
  }
  report.checks.push_back(solid);

  // 2. height field
  const std::string tolerance =
      options.normal_tolerance == 1e-3 ? std::string("1e-3") : fmt("%.4g", options.normal_tolerance);
  CheckReport height = named_check("height field (overhang cosine < -" + tolerance + " only on the base)");
  std::vector<HeightFieldReport> hf(n);
  {
    StageScope stage(progress, "check: height fields");
    HeightFieldOptions hopt;
    hopt.normal_tolerance = options.normal_tolerance;
    hopt.plane_tolerance = 1e-9 * std::max(1.0, diagonal);
    parallel_for(0, n, [&](std::size_t i) { hf[i] = check_height_field(blocks[i].mesh, blocks[i].direction, hopt); });
    double worst = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      worst = std::min(worst, hf[i].steepest_cosine);
      if (!hf[i].ok())
        add_failure(height, block_name(i) + ": " + std::to_string(hf[i].num_overhang_faces) +
                                " faces face away from the milling direction off the base (worst cosine " +
                                fmt("%.4f", hf[i].worst_cosine) + ")");
    }
    height.summary = "worst off-base cosine " + fmt("%.4g", worst) + " (" + fmt("%.2f", overhang_angle_deg(worst)) +
                     " deg past vertical)";
  }
  report.checks.push_back(height);

  // Within a tolerance, in decompose's frame when the folder has the frame
  // blocks (match_frame_blocks.h): there the blocks and the turned input
  // share their faces exactly, so the exact booleans of checks 3 and 4 are
  // cheaper (their volumes bounded back to the exported blocks) and check
  // 10 measures its parts there.
  const bool tolerant = options.tolerance > 0;
  std::optional<FrameMatch> frame;
  {
    bool in_frame = tolerant && options.frame_rotation.has_value() && n > 0;
    for (std::size_t i = 0; i < n && in_frame; ++i) in_frame = blocks[i].frame_mesh.has_value();
    if (in_frame) {
      std::vector<const Mesh*> exported(n), twins(n);
      for (std::size_t i = 0; i < n; ++i) {
        exported[i] = &blocks[i].mesh;
        twins[i] = &*blocks[i].frame_mesh;
      }
      frame = match_frame_blocks(input, exported, twins, *options.frame_rotation,
                                 {.snap_tolerance = options.frame_snap_tolerance});
    }
  }
  const auto matched = [&](std::size_t i) { return frame && frame->refused[i].empty(); };

  // 3. overlaps (exact booleans, only pairs whose boxes overlap)
  CheckReport overlap = named_check("no overlaps (volume <= 1e-6 of the smaller block)");
  {
    StageScope stage(progress, "check: overlaps");
    std::vector<BoundingBox> boxes(n);
    for (std::size_t i = 0; i < n; ++i) boxes[i] = bounding_box(blocks[i].mesh);
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if ((boxes[i].min.array() < boxes[j].max.array()).all() && (boxes[j].min.array() < boxes[i].max.array()).all())
          pairs.emplace_back(i, j);
    std::vector<double> vol(pairs.size(), 0.0);
    std::vector<char> bounded(pairs.size(), 0);  // settled by a rigorous bound, no boolean
    std::vector<std::string> errors(pairs.size());
    // The frames of the bounds: the input frame and each block's machine
    // frame (the canonical frame, where blocks meet on axis-aligned planes).
    std::vector<Eigen::Matrix3d> frames = {Eigen::Matrix3d::Identity()};
    std::vector<std::size_t> frame_of(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Matrix3d rot = blocks[i].machine_transform.topLeftCorner<3, 3>();
      if ((rot.transpose() * rot - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9) continue;
      const auto it = std::find(frames.begin(), frames.end(), rot);
      frame_of[i] = static_cast<std::size_t>(it - frames.begin());
      if (it == frames.end()) frames.push_back(rot);
    }
    const auto pair_frames = [&](std::size_t p) {
      std::vector<std::size_t> f = {0, frame_of[pairs[p].first], frame_of[pairs[p].second]};
      std::sort(f.begin(), f.end());
      f.erase(std::unique(f.begin(), f.end()), f.end());
      return f;
    };
    // 1. the slab bound (one separating plane of a frame)
    parallel_for(0, pairs.size(), [&](std::size_t p) {
      const Mesh& a = blocks[pairs[p].first].mesh;
      const Mesh& b = blocks[pairs[p].second].mesh;
      double bound = std::numeric_limits<double>::infinity();
      for (std::size_t f : pair_frames(p)) bound = std::min(bound, overlap_volume_bound(a, b, frames[f]));
      const double smaller = std::min(std::abs(volumes[pairs[p].first]), std::abs(volumes[pairs[p].second]));
      if (bound <= options.overlap_tolerance * smaller) {
        vol[p] = bound;
        bounded[p] = 1;
      }
    });
    // 2. the box bound (one block stays out of the other's bounding box), on
    // the blocks seen in the frames the remaining pairs need
    std::map<std::pair<std::size_t, std::size_t>, std::unique_ptr<detail::FramedBlock>> framed;  // (block, frame)
    for (std::size_t p = 0; p < pairs.size(); ++p)
      if (!bounded[p])
        for (std::size_t f : pair_frames(p)) {
          framed[{pairs[p].first, f}];
          framed[{pairs[p].second, f}];
        }
    {
      std::vector<std::pair<const std::pair<std::size_t, std::size_t>, std::unique_ptr<detail::FramedBlock>>*> slots;
      for (auto& entry : framed) slots.push_back(&entry);
      parallel_for(0, slots.size(), [&](std::size_t k) {
        try {
          slots[k]->second = std::make_unique<detail::FramedBlock>(blocks[slots[k]->first.first].mesh,
                                                                   frames[slots[k]->first.second]);
        } catch (const std::exception&) {
          // no box bound for this block (the booleans decide its pairs)
        }
      });
    }
    std::size_t num_box_bounded = 0;
    std::atomic<std::size_t> done{0};
    std::atomic<std::size_t> num_in_frame{0};  // exact pairs measured in decompose's frame
    parallel_for(0, pairs.size(), [&](std::size_t p) {
      if (bounded[p]) {
        if (progress) progress->update(++done, pairs.size());
        return;
      }
      const ValidationBlock& a = blocks[pairs[p].first];
      const ValidationBlock& b = blocks[pairs[p].second];
      const double smaller = std::min(std::abs(volumes[pairs[p].first]), std::abs(volumes[pairs[p].second]));
      double bound = std::numeric_limits<double>::infinity();
      for (std::size_t f : pair_frames(p)) {
        const auto& fa = framed.at({pairs[p].first, f});
        const auto& fb = framed.at({pairs[p].second, f});
        if (!fa || !fb) continue;
        bound = std::min({bound, detail::box_separation_bound(*fa, *fb), detail::box_separation_bound(*fb, *fa)});
        if (bound <= options.overlap_tolerance * smaller) break;
      }
      if (bound <= options.overlap_tolerance * smaller) {
        vol[p] = bound;
        bounded[p] = 2;
      } else {
        try {
          bool done_in_frame = false;
          if (matched(pairs[p].first) && matched(pairs[p].second)) {
            try {
              vol[p] = overlap_volume_bound(blocks_overlap(*a.frame_mesh, *b.frame_mesh), a.mesh, b.mesh, *frame);
              done_in_frame = true;
              ++num_in_frame;
            } catch (const std::exception&) {
              // the exported blocks, below (a refusal there is this check's failure)
            }
          }
          if (!done_in_frame) vol[p] = blocks_overlap(a.mesh, b.mesh);
        } catch (const std::exception& e) {
          errors[p] = e.what();
        }
      }
      if (progress) progress->update(++done, pairs.size());
    });
    double worst = 0.0, worst_bound = 0.0;
    std::size_t num_bounded = 0;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      const auto [i, j] = pairs[p];
      const std::string who = block_name(i) + " and " + block_name(j);
      if (!errors[p].empty()) {
        add_failure(overlap, who + ": boolean failed: " + errors[p]);
        continue;
      }
      const double smaller = std::max(std::min(std::abs(volumes[i]), std::abs(volumes[j])), 1e-300);
      const double ratio = vol[p] / smaller;
      if (bounded[p]) {
        ++num_bounded;
        if (bounded[p] == 2) ++num_box_bounded;
        worst_bound = std::max(worst_bound, ratio);
        continue;
      }
      worst = std::max(worst, ratio);
      if (ratio > options.overlap_tolerance)
        add_failure(overlap, who + " overlap by " + fmt("%.6g", vol[p]) + " (" + fmt("%.3g", ratio) +
                                 " of the smaller)");
    }
    overlap.summary = std::to_string(pairs.size()) + " pairs with overlapping bounding boxes: " +
                      std::to_string(num_bounded) + " bounded (" + std::to_string(num_bounded - num_box_bounded) +
                      " by a plane, " + std::to_string(num_box_bounded) + " by a bounding box; ratio <= " +
                      fmt("%.3g", worst_bound) + "), " + std::to_string(pairs.size() - num_bounded) + " exact" +
                      (frame ? " (" + std::to_string(num_in_frame.load()) +
                                   " in decompose's frame, volumes bounded back to the exported blocks)"
                             : std::string()) +
                      ", worst ratio " + fmt("%.3g", worst);
  }
  report.checks.push_back(overlap);

  // 4. inside the input
  std::vector<std::size_t> filled;  // blocks sticking out of the input (checked by check 10)
  // block \ input where check 4's boolean gave it, else its faces (a soup) where they could be classified
  std::vector<std::optional<Mesh>> outside_parts(n);
  std::vector<std::vector<char>> outside_on_input(n);  // per face of outside_parts[i]: on the input's surface
  std::vector<char> part_in_frame(n, 0);  // outside_parts[i] is block i's frame block \ the input in the frame
  CheckReport inside = named_check(tolerant ? "inside the input, or sticking out within the tolerance (check 10)"
                                            : "inside the input (volume outside <= 1e-6 of the block)");
  {
    StageScope stage(progress, "check: inside the input");
    std::vector<double> out(n, 0.0);
    std::vector<std::string> errors(n);
    std::atomic<std::size_t> done{0};
    // Within a tolerance, the part of each block outside the input is kept
    // for check 10, which measures the deviation only there.
    parallel_for(0, n, [&](std::size_t i) {
      try {
        if (tolerant) {
          detail::OutsidePart part;
          if (matched(i)) {
            try {
              part = detail::outside_part(*blocks[i].frame_mesh, frame->input);
              part_in_frame[i] = 1;
            } catch (const std::exception&) {
              // the exported block, below (a refusal there is this check's failure)
            }
          }
          if (!part_in_frame[i]) part = detail::outside_part(blocks[i].mesh, input);
          out[i] = part_in_frame[i] ? outside_volume_bound(part.volume, blocks[i].mesh, input, *frame) : part.volume;
          outside_parts[i] = part.mesh ? std::move(part.mesh) : std::move(part.boundary);
          outside_on_input[i] = std::move(part.on_input);
        } else {
          out[i] = volume_outside(blocks[i].mesh, input);  // no arena, no mesh kept: faster (kitten 45 vs 70 s)
        }
      } catch (const std::exception& e) {
        errors[i] = e.what();
      }
      if (progress) progress->update(++done, n);
    });
    double worst = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!errors[i].empty()) {
        add_failure(inside, block_name(i) + ": boolean failed: " + errors[i]);
        continue;
      }
      const double ratio = out[i] / std::max(std::abs(volumes[i]), 1e-300);
      report.volume_sticking_out += out[i];
      if (tolerant && ratio > options.outside_tolerance) {
        filled.push_back(i);
        continue;
      }
      worst = std::max(worst, ratio);
      if (ratio > options.outside_tolerance)
        add_failure(inside, block_name(i) + ": " + fmt("%.6g", out[i]) + " outside the input (" +
                                fmt("%.3g", ratio) + " of the block)");
    }
    inside.summary = "worst ratio outside " + fmt("%.3g", worst);
    if (frame) {
      const auto num_in_frame = static_cast<std::size_t>(std::count(part_in_frame.begin(), part_in_frame.end(), 1));
      inside.summary += "; " + std::to_string(num_in_frame) + " of " + std::to_string(n) +
                        " blocks measured in decompose's frame (volumes bounded back to the exported blocks)";
    }
    if (tolerant)
      inside.summary += " (" + std::to_string(filled.size()) + " block(s) sticking out: check 10; " +
                        fmt("%.4g", report.volume_sticking_out) + " outside the input in all)";
  }
  report.checks.push_back(inside);

  // 5. coverage
  CheckReport coverage = named_check(tolerant ? "surface coverage (samples within the tolerance of a block)"
                                              : "surface coverage (samples within 1e-5 x diagonal of a block)");
  {
    StageScope stage(progress, "check: coverage");
    std::vector<const Mesh*> meshes;
    for (const auto& b : blocks) meshes.push_back(&b.mesh);
    CoverageOptions copt;
    copt.num_samples = options.num_coverage_samples;
    copt.tolerance = std::max(options.coverage_tolerance * diagonal, options.tolerance);
    const CoverageReport c = surface_coverage(input, meshes, copt);
    coverage.summary = std::to_string(c.num_samples) + " samples, max distance " +
                       fmt("%.3g", c.max_distance / std::max(diagonal, 1e-300)) + " x diagonal";
    if (!c.ok())
      add_failure(coverage, std::to_string(c.num_uncovered) + " samples uncovered; worst at (" +
                                fmt("%.6g, %.6g, %.6g", c.worst_point.x(), c.worst_point.y(), c.worst_point.z()) +
                                ")");
  }
  report.checks.push_back(coverage);

  // 6. limits
  CheckReport limits = named_check("height and machine limits");
  {
    const double slack = options.limit_tolerance * diagonal;
    double tallest = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      tallest = std::max(tallest, hf[i].height);
      if (hf[i].height > options.limits.max_height + slack)
        add_failure(limits, block_name(i) + ": height " + fmt("%.6g", hf[i].height) + " > limit " +
                                fmt("%.6g", options.limits.max_height));
      if (options.limits.machine) {
        // Extent in the machine frame (from the machine transform's rotation).
        const Eigen::Matrix3d rot = blocks[i].machine_transform.topLeftCorner<3, 3>();
        BoundingBox bb;
        for (const Vec3& v : blocks[i].mesh.vertices) bb.extend(rot * v);
        const Vec3 size = bb.size();
        const Vec3& m = *options.limits.machine;
        const bool fits = size.z() <= m.z() + slack &&
                          ((size.x() <= m.x() + slack && size.y() <= m.y() + slack) ||
                           (size.x() <= m.y() + slack && size.y() <= m.x() + slack));
        if (!fits)
          add_failure(limits, block_name(i) + ": machine-frame size " +
                                  fmt("%.6g x %.6g x %.6g", size.x(), size.y(), size.z()) + " exceeds the machine");
      }
    }
    limits.summary = "tallest block " + fmt("%.6g", tallest) +
                     (std::isfinite(options.limits.max_height) ? ", limit " + fmt("%.6g", options.limits.max_height)
                                                                 : std::string(", no height limit")) +
                     (options.limits.machine ? ", machine limit set" : ", no machine limit");
  }
  report.checks.push_back(limits);

  // 7. machine meshes
  CheckReport machine = named_check("machine mesh = block moved rigidly, base on z = 0");
  {
    const double tol = options.limit_tolerance * std::max(diagonal, 1e-300);
    std::size_t checked = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const ValidationBlock& b = blocks[i];
      if (!b.machine_mesh) {
        add_failure(machine, block_name(i) + ": no machine mesh");
        continue;
      }
      ++checked;
      const Eigen::Matrix3d rot = b.machine_transform.topLeftCorner<3, 3>();
      const Vec3 shift = b.machine_transform.topRightCorner<3, 1>();
      const double orth = (rot.transpose() * rot - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
      if (orth > 1e-9 || rot.determinant() < 0 || (rot.transpose() * Vec3::UnitZ() - b.direction).norm() > 1e-9) {
        add_failure(machine, block_name(i) + ": machine transform is not a rotation taking the direction to +Z");
        continue;
      }
      const Mesh& mm = *b.machine_mesh;
      if (mm.num_faces() != b.mesh.num_faces()) {
        add_failure(machine, block_name(i) + ": machine mesh has " + std::to_string(mm.num_faces()) +
                                 " faces, block has " + std::to_string(b.mesh.num_faces()));
        continue;
      }
      double worst = 0.0;
      for (std::size_t f = 0; f < mm.num_faces(); ++f)
        for (int k = 0; k < 3; ++k) {
          const Vec3 p = rot * b.mesh.vertices[static_cast<std::size_t>(b.mesh.faces[f][static_cast<std::size_t>(k)])] + shift;
          const Vec3& q = mm.vertices[static_cast<std::size_t>(mm.faces[f][static_cast<std::size_t>(k)])];
          worst = std::max(worst, (p - q).norm());
        }
      const BoundingBox bb = bounding_box(mm);
      const double vol = signed_volume(mm);
      if (worst > tol)
        add_failure(machine, block_name(i) + ": machine mesh differs from the moved block by " + fmt("%.3g", worst));
      else if (std::abs(bb.min.z()) > tol)
        add_failure(machine, block_name(i) + ": machine base at z = " + fmt("%.6g", bb.min.z()) + ", not 0");
      else if (std::abs(bb.max.z() - hf[i].height) > tol)
        add_failure(machine, block_name(i) + ": machine height " + fmt("%.6g", bb.max.z()) + " != block height " +
                                 fmt("%.6g", hf[i].height));
      else if (std::abs(vol - volumes[i]) > 1e-5 * std::abs(volumes[i]))
        add_failure(machine, block_name(i) + ": machine volume " + fmt("%.6g", vol) + " != block volume " +
                                 fmt("%.6g", volumes[i]));
    }
    machine.summary = std::to_string(checked) + " machine meshes compared face by face";
  }
  report.checks.push_back(machine);

  // 8. machine meshes in single precision
  CheckReport single = named_check("machine meshes closed solids in single precision");
  {
    StageScope stage(progress, "check: single precision");
    std::vector<std::optional<SinglePrecisionReport>> sp(n);
    parallel_for(0, n, [&](std::size_t i) {
      if (blocks[i].machine_mesh) sp[i] = check_single_precision(*blocks[i].machine_mesh);
    });
    std::size_t checked = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!sp[i]) continue;  // check 7 reports the missing machine mesh
      ++checked;
      const SinglePrecisionReport& r = *sp[i];
      if (!r.ok())
        add_failure(single, block_name(i) + " in float32: " + std::to_string(r.num_welded) + " vertices welded, " +
                                std::to_string(r.solid.num_boundary_edges) + " boundary edges, " +
                                std::to_string(r.solid.num_non_manifold_edges) + " non-manifold edges, " +
                                std::to_string(r.solid.num_non_manifold_vertices) + " non-manifold vertices, " +
                                std::to_string(r.solid.num_degenerate_faces) + " zero-area faces, " +
                                std::to_string(r.num_self_intersections) + " self-intersecting face pairs");
    }
    single.summary = std::to_string(checked) + " machine meshes rounded to float32 and checked";
  }
  report.checks.push_back(single);

  // 9. no slivers
  CheckReport sliver =
      named_check("no slivers (thinner than max(1e-4 x diagonal, min(tolerance, max height / 4)) where the model is not)");
  {
    StageScope stage(progress, "check: slivers");
    report.sliver_thickness =
        sliver_threshold(options.sliver_thickness * diagonal, options.sliver_tolerance.value_or(options.tolerance),
                         options.limits.max_height);
    std::vector<SliverBlock> sb(n);
    for (std::size_t i = 0; i < n; ++i) {
      sb[i].mesh = &blocks[i].mesh;
      const Eigen::Matrix3d rot = blocks[i].machine_transform.topLeftCorner<3, 3>();
      if ((rot.transpose() * rot - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-9) sb[i].frame = rot;
    }
    if (n > 0 && report.sliver_thickness > 0)
      report.slivers = find_slivers(input, sb, {.min_thickness = report.sliver_thickness});
    double thinnest = std::numeric_limits<double>::infinity();
    std::size_t thinnest_block = 0, num_thin = 0;
    for (std::size_t i = 0; i < report.slivers.size(); ++i) {
      const SliverMeasure& m = report.slivers[i];
      if (m.thickness.thickness < thinnest) {
        thinnest = m.thickness.thickness;
        thinnest_block = i;
      }
      if (m.measured) ++num_thin;
      if (m.sliver)
        add_failure(sliver, block_name(i) + ": " + fmt("%.3g", m.thickness.thickness / std::max(diagonal, 1e-300)) +
                                " x diagonal thick where the model is " +
                                (m.num_chords == 0 ? std::string("not measured (no line crossed the block)")
                                                   : fmt("%.3g", m.model_chord / std::max(diagonal, 1e-300)) +
                                                         " x diagonal"));
    }
    sliver.summary = "thinnest " +
                     (report.slivers.empty() ? std::string("-")
                                             : block_name(thinnest_block) + " " +
                                                   fmt("%.3g", thinnest / std::max(diagonal, 1e-300)) + " x diagonal") +
                     "; " + std::to_string(num_thin) + " below " +
                     fmt("%.3g", report.sliver_thickness / std::max(diagonal, 1e-300)) + ", " +
                     std::to_string(sliver.num_failures) + " where the model is thicker";
  }
  report.checks.push_back(sliver);

  // 10. within the tolerance
  if (tolerant) {
    CheckReport within = named_check("within the tolerance (symmetric Hausdorff distance of input ∪ blocks to the input)");
    StageScope stage(progress, "check: tolerance");
    const double error = options.tolerance_error * options.tolerance;
    // In decompose's frame when check 4 matched the frame blocks.
    if (frame)
      for (std::size_t i = 0; i < n; ++i)
        if (!frame->refused[i].empty())
          add_failure(within, block_name(i) + ": frame block refused (frame/ does not match blocks/): " +
                                  frame->refused[i]);
    const Mesh& model = frame ? frame->input : input;
    const auto measured = [&](std::size_t i) -> const Mesh& { return frame ? *blocks[i].frame_mesh : blocks[i].mesh; };
    const FillDeviationMeter meter(model);
    std::vector<const Mesh*> sticking;
    for (std::size_t i : filled) sticking.push_back(&measured(i));
    // Only the points in the part of a block outside the input can deviate
    // (measure_fill_deviation.h, with C = block ∩ input): measured in boxes
    // that cover that part (check 4 computed it, in the frame when it
    // matched; made again there where check 4 had to use the exported block;
    // the columns of its faces where it is not a 2-manifold: solid_columns()
    // needs only its boundary), in the columns of the whole block where
    // neither could be made.
    std::vector<std::optional<std::vector<BoundingBox>>> cover(filled.size());
    std::vector<std::optional<Mesh>> frame_parts(filled.size());  // the parts made again in decompose's frame
    std::vector<std::vector<char>> frame_on_input(filled.size());
    std::vector<FillPart> part_of(filled.size());  // each block's part (either kind)
    std::vector<std::string> errors(filled.size());
    const auto parts_start = std::chrono::steady_clock::now();
    std::size_t num_made_again = 0;
    for (std::size_t i : filled) num_made_again += frame && !part_in_frame[i] && frame->refused[i].empty();
    parallel_for(0, filled.size(), [&](std::size_t k) {
      try {
        const std::size_t i = filled[k];
        if (frame && !part_in_frame[i]) {
          if (!frame->refused[i].empty()) return;
          detail::OutsidePart part = detail::outside_part(*sticking[k], model);
          if (part.mesh || part.boundary) {
            frame_parts[k] = part.mesh ? std::move(part.mesh) : std::move(part.boundary);
            frame_on_input[k] = std::move(part.on_input);
            part_of[k] = {&*frame_parts[k], &frame_on_input[k]};
            cover[k] = solid_columns(*frame_parts[k]);
          }
        } else if (outside_parts[i]) {
          part_of[k] = {&*outside_parts[i], &outside_on_input[i]};
          cover[k] = solid_columns(*outside_parts[i]);
        }
      } catch (const std::exception& e) {
        errors[k] = e.what();
      }
    });
    const double parts_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - parts_start).count();
    // Back to the exported blocks: stretch x D + the rounding (match_frame_blocks.h).
    const double stretch = frame ? frame->stretch : 1.0;
    const double rounding = frame ? frame->rounding() : 0.0;
    // First the cheap upper bound over each part's surface
    // (fill_deviation_upper_bound.h): a block it clears within the tolerance
    // is not measured in regions.
    const auto bound_start = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < filled.size(); ++k)
      if (!errors[k].empty() || (frame && !frame->refused[filled[k]].empty())) part_of[k] = {};
    FillDeviationUpperBounds upper;
    try {
      upper = fill_deviation_upper_bounds(model, sticking, part_of,
                                          {.error = error, .stop = options.tolerance / stretch, .coarse_fraction = 0.25});
    } catch (const std::exception&) {
      upper.blocks.assign(filled.size(), {});  // no bound (CGAL refused a distance query): measure them all
    }
    std::vector<char> cleared(filled.size(), 0);
    std::size_t num_cleared = 0;
    for (std::size_t k = 0; k < filled.size(); ++k)
      if (part_of[k].faces && stretch * upper.blocks[k].bound() + rounding <= options.tolerance) {
        cleared[k] = 1;
        ++num_cleared;
      }
    report.num_bounded_by_parts = num_cleared;
    if (progress) {
      std::size_t regions = 0;
      for (std::size_t k = 0; k < filled.size(); ++k)
        if (!cleared[k]) regions += cover[k] ? cover[k]->size() : 1;
      progress->info(std::to_string(num_cleared) + " of " + std::to_string(filled.size()) +
                     " block(s) sticking out within the tolerance by the bound over their parts' surfaces (" +
                     std::to_string(upper.target_faces) + " of " + std::to_string(upper.part_faces) +
                     " part faces on the model made for sure; " +
                     fmt("%.2f", std::chrono::duration<double>(std::chrono::steady_clock::now() - bound_start).count()) +
                     " s); measuring the deviation in " + std::to_string(regions) + " region(s) of the other " +
                     std::to_string(filled.size() - num_cleared) + " (their parts outside the input" +
                     (frame ? std::string(" from check 4 in decompose's frame, ") + std::to_string(num_made_again) +
                                  " made again there"
                            : std::string()) +
                     ": " + fmt("%.2f", parts_seconds) + " s)");
    }
    // each block near a box only where it sticks out near it (its part
    // elsewhere in the region lies in the input: the same model)
    FillCoverMap others_cover;
    for (std::size_t k = 0; k < filled.size(); ++k)
      if (cover[k]) others_cover.emplace(sticking[k], *cover[k]);
    // Refused frame blocks are not measured (the check has failed).
    std::vector<const Mesh*> to_measure;
    std::vector<std::optional<std::vector<BoundingBox>>> to_cover;
    std::vector<std::size_t> measured_index;
    for (std::size_t k = 0; k < filled.size(); ++k) {
      if (!errors[k].empty() || (frame && !frame->refused[filled[k]].empty()) || cleared[k]) continue;
      to_measure.push_back(sticking[k]);
      to_cover.push_back(cover[k]);
      measured_index.push_back(k);
    }
    std::vector<FillDeviation> dev(filled.size());
    const std::vector<FillDeviation> got =
        measure_fills(meter, to_measure, to_cover, sticking,
                      {.reach = options.tolerance, .error = error, .others_cover = &others_cover},
                      [&](std::size_t d, std::size_t total) {
                        if (progress) progress->update(d, total);
                      });
    for (std::size_t m = 0; m < measured_index.size(); ++m) dev[measured_index[m]] = got[m];
    for (std::size_t k = 0; k < filled.size(); ++k)
      if (cleared[k]) dev[k] = {upper.blocks[k].to_input, upper.blocks[k].from_input, 0.0, {}};  // error included
    report.num_filled = filled.size();
    report.deviation_error = stretch * error + rounding;
    report.measured_in_frame = frame.has_value();
    report.frame_rounding = rounding;
    for (std::size_t k = 0; k < filled.size(); ++k) {
      const std::string who = block_name(filled[k]);
      if (frame && !frame->refused[filled[k]].empty()) continue;  // reported above
      if (!errors[k].empty()) {
        add_failure(within, who + ": boolean failed: " + errors[k]);
        continue;
      }
      if (!dev[k].failure.empty()) {
        add_failure(within, who + ": " + dev[k].failure);
        continue;
      }
      const double to_input = stretch * dev[k].to_input, from_input = stretch * dev[k].from_input;
      const double bound = stretch * dev[k].bound() + rounding;
      report.deviation_to_input = std::max(report.deviation_to_input, to_input);
      report.deviation_from_input = std::max(report.deviation_from_input, from_input);
      if (bound > options.tolerance)
        add_failure(within, who + ": deviation up to " + fmt("%.6g", bound) + " > tolerance " +
                                fmt("%.6g", options.tolerance) + " (sticks out " + fmt("%.6g", to_input) +
                                ", buries the input " + fmt("%.6g", from_input) + ", error bound " +
                                fmt("%.3g", report.deviation_error) + ")");
    }
    // Blocks cleared by the bound report the bound (its error included, see
    // fill_deviation_upper_bound.h); the others what the exact measure gave.
    within.summary = std::to_string(filled.size()) + " block(s) sticking out (" + std::to_string(num_cleared) +
                     " within it by a bound over their parts' surfaces, " +
                     std::to_string(filled.size() - num_cleared) + " measured in regions); deviation " +
                     (num_cleared > 0 ? std::string("at most ") : std::string()) +
                     fmt("%.3g", std::max(report.deviation_to_input, report.deviation_from_input) /
                                     std::max(diagonal, 1e-300)) +
                     " x diagonal (" + (num_cleared > 0 ? std::string("bounds, their error included; ") : std::string()) +
                     "measures +- " + fmt("%.2g", report.deviation_error / std::max(diagonal, 1e-300)) +
                     "), tolerance " + fmt("%.3g", options.tolerance / std::max(diagonal, 1e-300)) +
                     (frame ? "; measured in decompose's frame (rounding back " +
                                  fmt("%.2g", rounding / std::max(diagonal, 1e-300)) + " x diagonal)"
                            : std::string());
    report.checks.push_back(within);
  }

  // Milled shapes (informational; exact blocks cost a height-field test).
  if (options.measure_milled_shapes) {
    std::vector<MilledBlockInput> mb(n);
    for (std::size_t i = 0; i < n; ++i) {
      mb[i].mesh = &blocks[i].mesh;
      mb[i].direction = blocks[i].direction;
      const Eigen::Matrix3d rot = blocks[i].machine_transform.topLeftCorner<3, 3>();
      if ((rot.transpose() * rot - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-9 &&
          rot.determinant() > 0 && (rot * blocks[i].direction - Vec3::UnitZ()).norm() <= 1e-9)
        mb[i].frame = rot;
    }
    MilledMeasureOptions mo;
    mo.hausdorff_error = options.milled_hausdorff_error;
    mo.progress = progress;
    report.milled = measure_milled_shapes(input, mb, mo);
  }
  return report;
}

}  // namespace subfab
