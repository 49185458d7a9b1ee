// SPDX-License-Identifier: GPL-3.0-or-later
// Overlap resolution (thesis Section 4.3.3): exact conflict tests on the
// solid, the graph work is in order_boxes.cpp.
#include "subfab/decompose/resolve_overlaps.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <tuple>
#include <string>

#include "decompose/order_boxes.h"
#include "decompose/resolve_overlaps_detail.h"
#include "geometry/triangle_meets_closed_box.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab::detail {

// Degenerate cases of the conflict test, and why the answer stays exact:
// - B1's face at level h equal to B2's base or top: conflict_region() gives
//   nothing. At the base the reversed face is part of the base plane (allowed);
//   at the top there is no part of B2 beyond it.
// - Boxes that only touch (no interior overlap): no region, no new face.
// - Triangles lying in the plane of B1's face inside the region's closure:
//   inside the open B2 they must face +d2 (B2 is valid), so the solid is
//   below them: they do not meet the open region (it starts strictly above
//   h), and the region's own answer decides.
// - Triangles meeting only the region's boundary (its side planes, or the
//   plane of B2's top): they do not meet the open region; whether the solid
//   fills the region is decided by the perturbed corner test, which is exact
//   because with no triangle inside, the open region is entirely inside or
//   entirely outside.
// - A triangle meeting the open region: points of the solid's interior lie
//   arbitrarily close to it on its inner side, inside the open region, so
//   material sits above B1's face within B2; since B2's block is closed
//   downwards along -d2 (every triangle in its open interior faces d2), that
//   material reaches B1's face over an open patch: a face with normal -d2
//   above the base, an invalid block.
// - The support boxes (the part of B2 below h outside B1) share faces; an
//   open set meets the solid's open interior iff one of the open boxes does.
namespace {
//! Exact: does the solid's interior meet the open box? Yes if a triangle
//! meets it (solid interior lies arbitrarily close beside the triangle);
//! otherwise the open box is entirely inside or outside, and the point
//! min + (e, e^2, e^3), which lies in it, tells which.
bool solid_meets_open_box(const SolidIndex& index, const Box3& box) {
  if (!(box.min.array() < box.max.array()).all()) return false;
  // Any triangle in the open box? Every triangle with a non-zero normal faces
  // away from at least one of the six axes, so this is the negation of box
  // validity for some axis (early-exit queries, unlike collecting all faces).
  // Zero-area triangles are in no list; in a closed mesh their points lie on
  // edges of non-degenerate triangles (refused as input anyway).
  for (Axis axis : kAllAxes)
    if (!index.box_is_valid(box, axis)) return true;
  return index.is_inside(box.min);
}
}  // namespace

bool carving_conflict(const SolidIndex& index, const HeightBox& first, const HeightBox& second) {
  const std::optional<Box3> region = conflict_region(first, second);
  if (!region || !solid_meets_open_box(index, *region)) return false;
  for (const Box3& support : conflict_support(first, second))
    if (solid_meets_open_box(index, support)) return true;
  return false;
}

std::vector<BoxTrim> conflict_trims(const SolidIndex& index, const HeightBox& first, const HeightBox& second,
                                    const std::function<double(const HeightBox&)>& size,
                                    const std::function<bool(const HeightBox&, const HeightBox&)>& keeps_surface) {
  std::vector<BoxTrim> trims;
  if (!carving_conflict(index, first, second)) return trims;
  for (int which = 0; which < 2; ++which) {
    const HeightBox& self = which == 0 ? first : second;
    const Box3& other = which == 0 ? second.box : first.box;
    auto conflict_with = [&](const Box3& moved) {
      const HeightBox hb{moved, self.axis, self.seed_face};
      return which == 0 ? carving_conflict(index, hb, second) : carving_conflict(index, first, hb);
    };
    for (int dim = 0; dim < 3; ++dim)
      for (int side : {-1, +1}) {
        // Move the face inward, at most until the overlap along dim is gone
        // (then there is no conflict); bisect for the least move that
        // breaks the edge (the answer is checked exactly at the end).
        const double cur = side > 0 ? self.box.max[dim] : self.box.min[dim];
        const double end = side > 0 ? std::max(self.box.min[dim], other.min[dim])
                                    : std::min(self.box.max[dim], other.max[dim]);
        if (side > 0 ? !(end < cur) : !(end > cur)) continue;
        Box3 moved = self.box;
        double& face = side > 0 ? moved.max[dim] : moved.min[dim];
        double bad = cur, good = end;
        face = good;
        if (conflict_with(moved)) continue;
        for (int it = 0; it < 64; ++it) {
          const double mid = bad + (good - bad) / 2;
          if (mid == bad || mid == good) break;
          face = mid;
          (conflict_with(moved) ? bad : good) = mid;
        }
        face = good;
        if (!(moved.min.array() < moved.max.array()).all()) continue;
        const HeightBox trimmed{moved, self.axis, self.seed_face};
        if (conflict_with(moved) || !keeps_surface(self, trimmed)) continue;
        trims.push_back(BoxTrim{which, moved, std::max(0.0, size(self) - size(trimmed))});
      }
  }
  return trims;
}

bool split_piece_droppable(const SolidIndex& index, const HeightBox& piece,
                           const std::function<bool(int face)>& covered_elsewhere) {
  const Box3& box = piece.box;
  if (!solid_meets_open_box(index, box)) return true;  // no volume: its block covers nothing
  // Otherwise every triangle touching the closed piece must be covered by
  // another live box (none touching: an interior chunk off the surface).
  // Candidates by closed bounding-box overlap (a linear scan of comparisons,
  // cheaper here than exact open-box tests on faces lying in the piece's
  // planes), then the cover counts, then the exact closed test.
  const Mesh& mesh = index.mesh();
  for (int f = 0; f < index.num_faces(); ++f) {
    const Box3& fb = index.face_box(f);
    if ((fb.min.array() > box.max.array()).any() || (fb.max.array() < box.min.array()).any()) continue;
    if (covered_elsewhere(f)) continue;
    const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
    if (triangle_meets_closed_box(mesh.vertices[static_cast<std::size_t>(t[0])],
                                  mesh.vertices[static_cast<std::size_t>(t[1])],
                                  mesh.vertices[static_cast<std::size_t>(t[2])], box))
      return false;
  }
  return true;
}

ResolveResult resolve_overlaps(const SolidIndex& index, std::vector<HeightBox> boxes, const ResolveOptions& options) {
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const Box3& b = boxes[i].box;
    if (!b.min.allFinite() || !b.max.allFinite() || (b.min.array() > b.max.array()).any())
      throw InvalidArgumentError("resolve_overlaps: box " + std::to_string(i) + " has non-finite or inverted corners");
  }
  std::vector<char> valid(boxes.size(), 0);
  parallel_for(0, boxes.size(), [&](std::size_t i) { valid[i] = index.box_is_valid(boxes[i]) ? 1 : 0; });
  for (std::size_t i = 0; i < boxes.size(); ++i)
    if (!valid[i])
      throw InvalidArgumentError("resolve_overlaps: box " + std::to_string(i) + " (axis " +
                                 std::string(axis_name(boxes[i].axis)) +
                                 ") is not a valid height box: a triangle facing away from its axis meets its interior");

  const BoundingBox bbox = bounding_box(index.mesh());
  BoxOrderCallbacks callbacks;
  callbacks.conflict = [&](const HeightBox& a, const HeightBox& b) { return carving_conflict(index, a, b); };
  // Per face, the number of live boxes covering it (SolidIndex::faces_covered).
  std::vector<int> cover_count(static_cast<std::size_t>(index.num_faces()), 0);
  {
    std::vector<std::vector<int>> covered(boxes.size());
    parallel_for(0, boxes.size(), [&](std::size_t i) { covered[i] = index.faces_covered(boxes[i]); });
    for (const auto& list : covered)
      for (int f : list) ++cover_count[static_cast<std::size_t>(f)];
  }
  // Faces covered by the box being split (asked for many candidate pieces).
  std::map<std::tuple<double, double, double, double, double, double, int>, std::vector<int>> covered_by_parent;
  callbacks.droppable = [&](const HeightBox& piece, const HeightBox& parent) {
    const Box3& pb = parent.box;
    const auto key = std::make_tuple(pb.min.x(), pb.min.y(), pb.min.z(), pb.max.x(), pb.max.y(), pb.max.z(),
                                     axis_index(parent.axis));
    auto it = covered_by_parent.find(key);
    if (it == covered_by_parent.end()) it = covered_by_parent.emplace(key, index.faces_covered(parent)).first;
    const std::vector<int>& by_parent = it->second;
    return split_piece_droppable(index, piece, [&](int f) {
      const bool parent_covers = std::binary_search(by_parent.begin(), by_parent.end(), f);
      return cover_count[static_cast<std::size_t>(f)] - (parent_covers ? 1 : 0) >= 1;
    });
  };
  callbacks.replaced = [&](const HeightBox& parent, const std::vector<HeightBox>& kept) {
    for (int f : index.faces_covered(parent)) --cover_count[static_cast<std::size_t>(f)];
    for (const HeightBox& piece : kept)
      for (int f : index.faces_covered(piece)) ++cover_count[static_cast<std::size_t>(f)];
  };
  callbacks.size = [&](const HeightBox& b) {
    Box3 clipped{b.box.min.cwiseMax(bbox.min), b.box.max.cwiseMin(bbox.max)};
    return clipped.volume();
  };
  callbacks.trims = [&](const HeightBox& first, const HeightBox& second) {
    return conflict_trims(index, first, second, callbacks.size, [&](const HeightBox& old_box, const HeightBox& trimmed) {
      // A trim drops the slab old \ trimmed, so it must be droppable like a
      // split piece: every triangle touching the slab is covered by the
      // trimmed box or by another live box. Checking only the faces the old
      // box covered (entirely) is not enough: after splits a triangle can be
      // covered by several boxes together and by none alone (its cover count
      // is 0), and the slab may hold the only part of it that is covered.
      const std::vector<int> before = index.faces_covered(old_box);
      const std::vector<int> after = index.faces_covered(trimmed);
      auto covered_elsewhere = [&](int f) {
        if (std::binary_search(after.begin(), after.end(), f)) return true;
        const bool old_covers = std::binary_search(before.begin(), before.end(), f);
        return cover_count[static_cast<std::size_t>(f)] - (old_covers ? 1 : 0) >= 1;
      };
      for (const Box3& slab : box_difference(old_box.box, trimmed.box, {0, 1, 2}))
        if (!split_piece_droppable(index, HeightBox{slab, old_box.axis, -1}, covered_elsewhere)) return false;
      return true;
    });
  };
  BoxOrderOptions order_options;
  order_options.max_splits = options.max_splits;
  order_options.progress = options.progress;
  BoxOrderResult ordered = order_boxes(std::move(boxes), callbacks, order_options);

  ResolveResult result;
  result.ordered = std::move(ordered.ordered);
  result.num_splits = ordered.num_splits;
  result.num_trims = ordered.num_trims;
  result.num_dropped_pieces = ordered.num_dropped_pieces;
  result.num_conflict_edges = ordered.num_initial_edges;
  result.num_boxes_on_cycles = ordered.num_initial_cyclic;
  if (options.progress)
    options.progress->info("resolve: " + std::to_string(result.num_conflict_edges) + " conflict edges, " +
                           std::to_string(result.num_boxes_on_cycles) + " boxes on cycles, " +
                           std::to_string(result.num_trims) + " trims, " + std::to_string(result.num_splits) +
                           " splits, " +
                           std::to_string(result.num_dropped_pieces) + " pieces dropped, " +
                           std::to_string(result.ordered.size()) + " boxes in carve order");
  return result;
}

}  // namespace subfab::detail

namespace subfab {

ResolveResult resolve_overlaps(const Mesh& mesh, std::vector<HeightBox> boxes, const ResolveOptions& options) {
  const detail::SolidIndex index(mesh, overhang_sine(options.max_overhang_deg), options.allowed_overhangs,
                                 options.overhang_floors);
  return detail::resolve_overlaps(index, std::move(boxes), options);
}

}  // namespace subfab
