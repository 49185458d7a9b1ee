// SPDX-License-Identifier: GPL-3.0-or-later
// Overlap resolution (thesis Section 4.3.3): exact conflict tests on the
// solid, the graph work is in order_boxes.cpp.
#include "subfab/decompose/resolve_overlaps.h"

#include <cmath>
#include <limits>
#include <string>

#include "decompose/order_boxes.h"
#include "decompose/resolve_overlaps_detail.h"
#include "decompose/triangle_meets_closed_box.h"
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
  if (!index.faces_meeting_open_box(box).empty()) return true;
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

bool split_piece_droppable(const SolidIndex& index, const HeightBox& piece) {
  const Box3& box = piece.box;
  if (!index.faces_meeting_open_box(box).empty()) return false;
  if (!index.is_inside(box.min)) return true;  // the block is empty
  // An interior chunk: droppable iff no triangle touches the closed box.
  // Candidates: faces meeting a slightly larger open box (which contains the
  // closed box), then the exact closed test.
  Box3 grown = box;
  for (int k = 0; k < 3; ++k) {
    grown.min[k] = std::nextafter(box.min[k], -std::numeric_limits<double>::infinity());
    grown.max[k] = std::nextafter(box.max[k], std::numeric_limits<double>::infinity());
  }
  const Mesh& mesh = index.mesh();
  for (int f : index.faces_meeting_open_box(grown)) {
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
  callbacks.droppable = [&](const HeightBox& piece) { return split_piece_droppable(index, piece); };
  callbacks.size = [&](const HeightBox& b) {
    Box3 clipped{b.box.min.cwiseMax(bbox.min), b.box.max.cwiseMin(bbox.max)};
    return clipped.volume();
  };
  BoxOrderOptions order_options;
  order_options.max_splits = options.max_splits;
  order_options.progress = options.progress;
  BoxOrderResult ordered = order_boxes(std::move(boxes), callbacks, order_options);

  ResolveResult result;
  result.ordered = std::move(ordered.ordered);
  result.num_splits = ordered.num_splits;
  result.num_dropped_pieces = ordered.num_dropped_pieces;
  result.num_conflict_edges = ordered.num_initial_edges;
  result.num_boxes_on_cycles = ordered.num_initial_cyclic;
  if (options.progress)
    options.progress->info("resolve: " + std::to_string(result.num_conflict_edges) + " conflict edges, " +
                           std::to_string(result.num_boxes_on_cycles) + " boxes on cycles, " +
                           std::to_string(result.num_splits) + " splits, " +
                           std::to_string(result.num_dropped_pieces) + " pieces dropped, " +
                           std::to_string(result.ordered.size()) + " boxes in carve order");
  return result;
}

}  // namespace subfab::detail

namespace subfab {

ResolveResult resolve_overlaps(const Mesh& mesh, std::vector<HeightBox> boxes, const ResolveOptions& options) {
  const detail::SolidIndex index(mesh);
  return detail::resolve_overlaps(index, std::move(boxes), options);
}

}  // namespace subfab
