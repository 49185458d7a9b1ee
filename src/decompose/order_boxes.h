// SPDX-License-Identifier: GPL-3.0-or-later
//! \file order_boxes.h
//! The pure graph part of overlap resolution (thesis Section 4.3.3), written
//! against callbacks so that it can be tested with synthetic conflicts; the
//! geometry (the exact conflict test) lives in resolve_overlaps.cpp.
//!
//! Outline of order_boxes():
//!   1. conflict graph: edge a -> b iff carving box a before box b would leave
//!      the block of b invalid (callback `conflict`, asked only for pairs whose
//!      interiors overlap, in parallel);
//!   2. while a strongly connected component with two or more vertices exists
//!      (Tarjan, recomputed after every split; never all cycles):
//!        - take the component holding the smallest live vertex id s and a
//!          shortest cycle through s (BFS inside the component);
//!        - first, if a trim breaks an edge of the cycle without losing
//!          surface (callback `trims`: one face of a or b moved inward), the
//!          one removing the least is applied: no new box (thesis 4.3.4's
//!          shrinking, aimed at the conflicts; bounded by max_trims);
//!        - otherwise, for every edge a -> b of that cycle, candidate split: B_b minus
//!          B_a as at most 6 disjoint sub-boxes of B_b (box_difference, best of
//!          the 6 cutting orders), minus the droppable pieces; score = size of
//!          the smallest kept piece; choose the edge with the largest score
//!          (ties: fewer pieces, then the earlier edge on the cycle);
//!        - replace b by its kept pieces and test their edges against the
//!          boxes that overlapped b;
//!      Every split removes the overlap volume of a and b and creates no new
//!      overlap, and all box coordinates come from the input coordinates, so
//!      the loop ends; a cap (options.max_splits) turns a bug into an error.
//!   3. order: Kahn's algorithm on the reversed graph (a box is ready when
//!      every box it points to has been output), always taking the ready box
//!      of smallest size (ties: smaller id) first.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/geometry/height_box.h"

namespace subfab::detail {

//! A way to break one conflict edge without a new box: one of its two
//! boxes replaced by a sub-box of itself (one face moved inward).
struct BoxTrim {
  int which = 0;       // 0: the edge's first box, 1: its second box
  Box3 box;            // the trimmed box (a sub-box of the old one, positive volume)
  double removed = 0;  // size lost (the `size` callback's measure), >= 0
};

//! What order_boxes needs to know about the geometry. All callbacks must be
//! deterministic and safe to call concurrently.
struct BoxOrderCallbacks {
  //! Edge first -> second: carving `first` before `second` (so that second's
  //! block becomes solid ∩ (second \ first)) leaves an invalid block.
  //! Called only for boxes whose interiors overlap.
  std::function<bool(const HeightBox& first, const HeightBox& second)> conflict;
  //! A piece of `parent` made by a split may be dropped without losing any
  //! part of the surface (given the live boxes other than `parent`). Called
  //! serially. Null = keep all.
  std::function<bool(const HeightBox& piece, const HeightBox& parent)> droppable;
  //! Told (serially) that `parent` was replaced by `kept`. May be null.
  std::function<void(const HeightBox& parent, const std::vector<HeightBox>& kept)> replaced;
  //! Trims that break the edge first -> second (the edge is gone with the
  //! trimmed box, and no surface is lost given the live boxes), smallest
  //! first preferred. Called serially. Null = never trim (split only).
  std::function<std::vector<BoxTrim>(const HeightBox& first, const HeightBox& second)> trims;
  //! Deterministic size of the block of a box (>= 0; smaller blocks are
  //! carved first, splits keep the smallest piece large).
  std::function<double(const HeightBox& box)> size;
};

//! Options of order_boxes().
struct BoxOrderOptions {
  int max_splits = 100000;       // cap on cycle-breaking splits (AlgorithmError beyond it)
  int max_trims = -1;            // cap on cycle-breaking trims (-1: 4 x the number of boxes); splits after it
  Progress* progress = nullptr;  // stage reporting (nullptr = silent)
};

//! Result of order_boxes().
struct BoxOrderResult {
  std::vector<HeightBox> ordered;      // carve order: ordered[0] is carved first
  int num_splits = 0;                  // boxes replaced by their pieces
  int num_trims = 0;                   // boxes replaced by a trimmed sub-box (no new box)
  int num_dropped_pieces = 0;          // pieces of splits left out (droppable)
  std::size_t num_initial_edges = 0;   // conflict edges before any split
  std::size_t num_final_edges = 0;     // conflict edges of the final DAG
  std::size_t num_initial_cyclic = 0;  // boxes in non-trivial strongly connected components at the start
};

//! Splits cycles and orders the boxes (see the file comment).
//! \throw AlgorithmError if options.max_splits splits do not make the graph acyclic.
BoxOrderResult order_boxes(std::vector<HeightBox> boxes, const BoxOrderCallbacks& callbacks,
                           const BoxOrderOptions& options);

//! b \ cut as disjoint closed boxes, each a sub-box of b with a positive
//! volume, whose union is the closure of b \ cut. `dims` is the cutting order:
//! first the slabs of b below and above cut along dims[0], then in the middle
//! slab along dims[1], then along dims[2] (at most 6 boxes). Coordinates are
//! copied from b and cut, never computed. Empty when cut contains b; {b} when
//! the interiors do not overlap.
std::vector<Box3> box_difference(const Box3& b, const Box3& cut, const std::array<int, 3>& dims);

//! Geometry of the conflict test (thesis Section 4.3.3; the solid decides
//! it exactly in resolve_overlaps.cpp). Carving `first` (B1) before `second`
//! (B2, axis d along dimension k) gives B2 the block K = solid ∩ (B2 \ B1).
//! K is bounded by input triangles inside B2 (all facing d or sideways when
//! B2 is valid), parts of B2's faces (fine) and parts of B1's faces with
//! reversed normals: a face of B1 with outward normal e becomes one with
//! normal -e, which can only break the height field for e = d, i.e. B1's face
//! at level h on B2's +d side, and only when h is strictly between B2's base
//! and top. Then K is invalid iff
//!   (a) the solid's interior meets the open conflict_region(): the part of
//!       B2 beyond h across the overlap of B1 and B2 (for a valid B2 the solid
//!       in B2 is closed downwards along -d, so material there reaches B1's
//!       face over an open patch: a face of K with normal -d at level h), and
//!   (b) the solid's interior meets one of the conflict_support() boxes: the
//!       part of B2 below h (along d) outside B1 (so K has material below h
//!       and that face is not on K's base plane).
//! Without (a) no face of K faces -d above B2's base; without (b) all of K
//! lies beyond h and B1's face is K's base. Coordinates are copied from the
//! boxes (exact). nullopt / empty when geometry alone rules a conflict out.
std::optional<Box3> conflict_region(const HeightBox& first, const HeightBox& second);
//! See conflict_region(): closed boxes with disjoint interiors whose interiors
//! cover the part of second's box below first's +d face (along second's axis
//! d) outside first's box. Empty when conflict_region() is nullopt.
std::vector<Box3> conflict_support(const HeightBox& first, const HeightBox& second);

//! Strongly connected components of a directed graph on vertices
//! 0..n-1 (adjacency lists `out`; vertices with alive[v] == 0 are ignored):
//! component id per vertex (-1 for dead vertices), ids in order of discovery
//! from the smallest vertex. Iterative Tarjan, O(n + e).
std::vector<int> strongly_connected_components(const std::vector<std::vector<int>>& out,
                                               const std::vector<char>& alive);

}  // namespace subfab::detail
