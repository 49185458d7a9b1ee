// SPDX-License-Identifier: GPL-3.0-or-later
//! \file block_pairs_detail.h
//! Private: what the two merges of touching blocks share (merge_blocks,
//! thesis Section 4.3.4, and merge_within_tolerance): the per-block boxes
//! and volumes a round starts from, the touch test that picks the pairs,
//! the height and machine limits, and the exact union of two blocks.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "geometry/box_tests.h"
#include "geometry/exact_mesh.h"
#include "geometry/solid_index.h"
#include "subfab/decompose/carve_blocks.h"

namespace subfab::detail {

//! The bounding box of each block's mesh, in order.
std::vector<BoundingBox> block_boxes(const std::vector<Block>& blocks);

//! The signed volume of each block's mesh, in order.
std::vector<double> block_volumes(const std::vector<Block>& blocks);

//! Does a block with bounding box `box` milled along `axis` fit: its extent
//! along the axis at most `max_height` and machine_size.z(), its other two
//! extents within machine_size.x() and .y() (either way round)? Model units.
bool within_limits(const BoundingBox& box, Axis axis, double max_height, const Vec3& machine_size);

//! What a milled shape M adds to a solid C that overlaps no block: the
//! fill G = closure(M \ C), covered by `tiles` (fill_columns()) and, finer,
//! by `columns` (fill_face_columns()). M can then overlap a block only in
//! G. `index_of(k)` gives block k's inside_test_index() (built on first
//! use; nullptr when the exact booleans refuse the block).
struct AddedFill {
  const std::vector<BoundingBox>* tiles = nullptr;
  const std::vector<BoundingBox>* columns = nullptr;
  std::function<const SolidIndex*(std::size_t)> index_of;
};

//! Does the block mesh `m` overlap one of `blocks` (those `skip` does not
//! exclude; `boxes` and `volumes` theirs) by more than `tolerance` x the
//! smaller volume? A bound from the boxes first (overlap_volume_bound()),
//! then the exact volume (validate's overlap check); an exact boolean that
//! fails counts as an overlap. With `added` (m = C + G, C overlapping no
//! block), a block none of whose interior meets a box of G
//! (fill_misses_solid(), exact) is not checked further, and the exact
//! volume is computed with both clipped near the boxes that meet it.
bool overlaps_a_block(const Mesh& m, const std::vector<Block>& blocks, const std::vector<BoundingBox>& boxes,
                      const std::vector<double>& volumes, const std::function<bool(std::size_t)>& skip,
                      double tolerance, const AddedFill* added = nullptr);

//! Extends `region` by each box of `fill` whose interior meets `other`,
//! clipped to `other`: where a shape that adds `fill` can overlap a solid
//! in the box `other`.
void extend_by_fill_boxes(const std::vector<BoundingBox>& fill, const BoundingBox& other, BoundingBox& region);

//! The box around all of `fill`, widened by 1e-3 of the larger of its and
//! `block`'s diagonals (so that no plane of it is a face's plane by
//! accident): what a block's part outside the input is clipped to when that
//! part lies in its fill (detail::outside_part()).
BoundingBox fill_hull(const std::vector<BoundingBox>& fill, const BoundingBox& block);

//! The SolidIndex of a block the exact booleans accept (no zero-area face,
//! no self-intersection, exact checks: its inside test is then
//! meaningful), else nullptr. (A zero-area face left by rounding makes its
//! neighbours overlap along a segment, which the self-intersection check
//! reports anyway.)
std::unique_ptr<SolidIndex> inside_test_index(const Mesh& block);

//! Exact: does the interior of the solid `index` indexes (bounding box
//! `solid_box`) miss the open interior of every box of `fill` (each
//! clipped to `solid_box`)? For each box: no face of the solid meets it,
//! and a point just inside it is outside the solid. Two milled shapes whose
//! carved blocks do not overlap cannot overlap when each one's interior
//! misses the other's fill boxes (fill_columns()).
bool fill_misses_solid(const std::vector<BoundingBox>& fill, const SolidIndex& index, const BoundingBox& solid_box);

//! The union of blocks a and b, computed exactly (CGAL corefinement on the
//! exact kernel, in a private DeterministicArena) and rounded to doubles
//! (how that went in `rounding`), when it is non-empty, `accept` (if set)
//! holds for the exact union, and it is one connected piece. Nullopt when
//! either mesh has a degenerate face or the exact boolean fails or throws
//! (then: do not merge the pair). `accept` runs inside the arena.
std::optional<Mesh> exact_block_union(const Mesh& a, const Mesh& b,
                                      const std::function<bool(const ExactMesh&)>& accept, RoundingReport& rounding);

//! The union of several blocks, exactly (successive exact unions, one
//! rounding at the end), as the pair version: nullopt unless every union is
//! a 2-manifold, the result one connected piece and `accept` holds.
std::optional<Mesh> exact_block_union(const std::vector<const Mesh*>& meshes,
                                      const std::function<bool(const ExactMesh&)>& accept, RoundingReport& rounding);

}  // namespace subfab::detail
