// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/validate/fill_deviation_upper_bound.h"

#include <CGAL/squared_distance_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <mutex>

#include "geometry/box_tests.h"
#include "geometry/surface_deviation.h"
#include "geometry/triangle_tree.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/validate/measure_fill_deviation.h"
#include "validate/lazy_solid.h"

namespace subfab {
namespace {

//! How much of a face next to another block a target keeps: the face shrunk
//! towards its centroid by this fraction (its rim, where it may touch the
//! other block, is not a target; a point of the rim lies within this
//! fraction of the face's size from the shrunk face).
constexpr double kShrink = 1e-3;

}  // namespace

FillDeviationUpperBounds fill_deviation_upper_bounds(const Mesh& solid, const std::vector<const Mesh*>& filled,
                                                     const std::vector<FillPart>& parts,
                                                     const FillDeviationUpperBoundOptions& options,
                                                     const std::vector<char>& which) {
  const double error = options.error, stop = options.stop;
  const std::size_t n = filled.size();
  if (parts.size() != n || (!which.empty() && which.size() != n))
    throw InvalidArgumentError("fill_deviation_upper_bounds: one part and one flag per filled block expected");
  if (!(error > 0) || !(options.coarse_fraction >= 0))
    throw InvalidArgumentError(
        "fill_deviation_upper_bounds: the error bound must be > 0 and the coarse fraction >= 0");
  for (const FillPart& p : parts)
    if (p.faces && (!p.on_input || p.on_input->size() != p.faces->faces.size()))
      throw InvalidArgumentError("fill_deviation_upper_bounds: one on-input flag per part face expected");
  FillDeviationUpperBounds out;
  out.blocks.resize(n);
  if (n == 0 || solid.faces.empty()) return out;

  std::vector<BoundingBox> boxes(n);
  for (std::size_t k = 0; k < n; ++k) boxes[k] = bounding_box(*filled[k]);
  double scale = largest_coordinate(solid);
  for (const Mesh* m : filled) scale = std::max(scale, largest_coordinate(*m));
  const double contact = 1e-10 * std::max(scale, 1e-300);  // far above the parts' rounding
  const auto widened = [&](BoundingBox b) {
    b.min.array() -= contact;
    b.max.array() += contact;
    return b;
  };
  std::vector<detail::LazySolid> blocks(n);
  // Per pair of filled blocks whose boxes meet: an axis-aligned plane
  // between them, exactly (decompose's blocks meet on such planes).
  struct Between {
    int axis = -1;  // -1: no such plane
    double at = 0.0;
  };
  std::vector<std::vector<std::pair<std::size_t, Between>>> near(n);  // per block: (other, plane)
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t j = 0; j < n; ++j) {
      if (j == k || !detail::boxes_touch(boxes[k], boxes[j])) continue;
      Between p;
      for (int a = 0; a < 3 && p.axis < 0; ++a) {
        if (boxes[k].max[a] <= boxes[j].min[a]) p = {a, boxes[k].max[a]};
        else if (boxes[j].max[a] <= boxes[k].min[a]) p = {a, boxes[k].min[a]};
      }
      near[k].emplace_back(j, p);
    }

  // The targets: per part, its faces (or the inner part of a face, shrunk
  // towards its centroid) that lie on ∂U for sure (file comment); each
  // target face as three vertices of its own.
  std::vector<Mesh> targets(n);
  std::vector<std::vector<char>> whole_target(n);  // per part face: a target whole
  parallel_for(0, n, [&](std::size_t k) {
    if (!parts[k].faces) return;
    const Mesh& part = *parts[k].faces;
    Mesh& out_k = targets[k];
    whole_target[k].assign(part.faces.size(), 0);
    for (std::size_t f = 0; f < part.faces.size(); ++f) {
      if ((*parts[k].on_input)[f]) continue;
      const Triangle& t = part.faces[f];
      std::array<Vec3, 3> corner;
      BoundingBox box;
      for (int q = 0; q < 3; ++q) {
        corner[static_cast<std::size_t>(q)] = part.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>(q)])];
        box.extend(corner[static_cast<std::size_t>(q)]);
      }
      const Vec3 centroid = (corner[0] + corner[1] + corner[2]) / 3.0;
      // Whole when a plane between the blocks keeps the face off every F_j's
      // plane of contact; else its inner part, tested against F_j's faces.
      bool whole = true, inner = true;
      std::array<Vec3, 3> shrunk;
      for (std::size_t q = 0; q < 3; ++q) shrunk[q] = centroid + (1.0 - kShrink) * (corner[q] - centroid);
      const detail::TriangleTree::Triangle3 small(detail::TriangleTree::point(shrunk[0]),
                                                  detail::TriangleTree::point(shrunk[1]),
                                                  detail::TriangleTree::point(shrunk[2]));
      if (small.is_degenerate()) continue;
      for (const auto& [j, p] : near[k]) {
        if (p.axis >= 0 && !(box.min[p.axis] == p.at && box.max[p.axis] == p.at)) continue;  // F_j beyond the plane
        whole = false;
        const BoundingBox w = widened(box);
        if (!detail::boxes_touch(w, boxes[j])) continue;
        blocks[j].build(*filled[j]);
        std::vector<detail::TriangleTree::Iterator> hit;
        blocks[j].surface->tree().all_intersected_primitives(
            CGAL::Bbox_3(w.min.x(), w.min.y(), w.min.z(), w.max.x(), w.max.y(), w.max.z()), std::back_inserter(hit));
        for (const auto& it : hit)
          if (it->is_degenerate() || !(CGAL::squared_distance(small, *it) > contact * contact)) {
            inner = false;  // (a degenerate face of F_j counts as touching: conservative)
            break;
          }
        if (inner && blocks[j].index->is_inside(centroid)) inner = false;
        if (!inner) break;
      }
      if (!whole && !inner) continue;
      whole_target[k][f] = whole;
      const int base = static_cast<int>(out_k.vertices.size());
      for (const Vec3& v : whole ? corner : shrunk) out_k.vertices.push_back(v);
      out_k.faces.push_back({base, base + 1, base + 2});
    }
  });
  // ∂S near the parts: their faces on it (a part of ∂S: distances to it
  // bound those to ∂S; CGAL refines a face lying just off ∂S across several
  // of its faces a long way down, where it finds the part's own face under
  // it at once); ∂S whole for the blocks that bound does not clear.
  detail::DistanceMesh to_solid, near_solid, to_targets;
  for (std::size_t k = 0; k < n; ++k)
    if (parts[k].faces) {
      std::vector<int> on;
      for (std::size_t f = 0; f < parts[k].faces->faces.size(); ++f)
        if ((*parts[k].on_input)[f]) on.push_back(static_cast<int>(f));
      detail::append_distance_patch(near_solid, *parts[k].faces, &on);
    }
  double target_rounding = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (!parts[k].faces) continue;
    out.part_faces += parts[k].faces->faces.size();
    out.target_faces += targets[k].faces.size();
    if (targets[k].faces.empty()) continue;
    detail::append_distance_patch(to_targets, targets[k], nullptr);
    // a shrunk face's corners are computed in doubles: within a few ulps of the exact ones
    target_rounding = std::max(target_rounding, 2.0 * rounding_slack(targets[k]));
  }
  double part_rounding = 0.0;
  for (const FillPart& p : parts)
    if (p.faces) part_rounding = std::max(part_rounding, rounding_slack(*p.faces));
  std::once_flag solid_once;

  // Two passes when asked (options.coarse_fraction): first within a coarse
  // error, then within `error` the blocks the first does not clear.
  const double coarse = std::isfinite(stop) ? std::max(error, options.coarse_fraction * stop) : error;
  const auto bound = [&](std::size_t k, double e) {
    // Sources: every face for the distance to the targets but the whole
    // targets (0); only the faces off ∂S for the distance to ∂S (the others
    // lie on it: 0).
    detail::DistanceMesh from, off_input;
    std::vector<int> off, buried;
    for (std::size_t f = 0; f < parts[k].faces->faces.size(); ++f) {
      if (!(*parts[k].on_input)[f]) off.push_back(static_cast<int>(f));
      if (!whole_target[k][f]) buried.push_back(static_cast<int>(f));
    }
    detail::append_distance_patch(off_input, *parts[k].faces, &off);
    detail::append_distance_patch(from, *parts[k].faces, &buried);
    const double slack = rounding_slack(*parts[k].faces);
    FillDeviationUpperBound b;
    b.to_input = detail::one_sided_hausdorff(off_input, near_solid, e) + e + slack + part_rounding;
    if (b.to_input > stop) {
      std::call_once(solid_once, [&] { detail::append_distance_patch(to_solid, solid, nullptr); });
      b.to_input = std::min(b.to_input, detail::one_sided_hausdorff(off_input, to_solid, e) + e + slack);
    }
    if (to_targets.number_of_faces() > 0)
      b.from_input = detail::one_sided_hausdorff(from, to_targets, e) + e + slack + target_rounding;
    return b;
  };
  parallel_for(0, n, [&](std::size_t k) {
    if (!parts[k].faces || (!which.empty() && !which[k])) return;
    out.blocks[k] = bound(k, coarse);
    if (coarse > error && out.blocks[k].bound() > stop) out.blocks[k] = bound(k, error);
  });
  return out;
}

}  // namespace subfab
