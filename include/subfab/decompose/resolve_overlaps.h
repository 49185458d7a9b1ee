// SPDX-License-Identifier: GPL-3.0-or-later
//! \file resolve_overlaps.h
//! Overlap resolution (thesis Section 4.3.3): orders the chosen boxes so that
//! carving them one after the other (block_k = solid ∩ B_k minus the boxes
//! carved before) gives valid height-field blocks, splitting boxes where the
//! conflict graph has cycles.
//!
//! Outline of resolve_overlaps():
//!   1. conflict graph: edge b1 -> b2 iff solid ∩ (B2 \ B1) is not a valid
//!      height-field block, decided exactly: with d2 the axis of b2, B1's face
//!      on the +d2 side must lie strictly between B2's base and top, and the
//!      solid's interior must meet the open box R x (that face, B2's top),
//!      R = the open overlap of B1 and B2 across d2 (see conflict_region in
//!      src/decompose/order_boxes.h for why this is exact for a valid B2);
//!   2. per strongly connected component, a shortest cycle is broken by
//!      trimming one of its boxes (one face moved inward just enough to
//!      remove a conflict edge, when the removed slab could be dropped like a
//!      split piece: every triangle touching it is covered by the trimmed box
//!      or by another live box; the least removed volume first), or else by
//!      splitting the head b2 of one of its edges b1 -> b2 into sub-boxes of
//!      B2 \ B1 (sub-boxes of a valid box are valid), choosing the edge whose
//!      smallest kept piece is largest; a piece is dropped when its block is
//!      empty, touches no surface, or every triangle it touches is covered
//!      by another live box; repeated until acyclic;
//!   3. order: Kahn's algorithm on the reversed graph, smallest block first.
//!
//! Surface coverage is kept: a split keeps the union of the boxes (B1 stays,
//! the pieces fill B2 \ B1), a trim is a split into the trimmed box and a
//! dropped slab, and a dropped piece or slab either holds no solid, or
//! touches no surface, or every triangle it touches lies in another live box
//! with the solid on that box's side (cover counts are kept up to date over
//! splits), so every surface point that had solid of some box next to it
//! still has. The carve stage works on volumes, so this is what it needs.
//! Pairwise validity suffices for the sequence: the new faces of block_k are
//! parts of faces of earlier boxes, each a subset of the pairwise case.
#pragma once

#include <array>
#include <cstdint>

#include <cstddef>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/geometry/height_box.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of resolve_overlaps().
struct ResolveOptions {
  int max_splits = 10000;        // cap on cycle-breaking splits (AlgorithmError beyond it)
  double max_overhang_deg = 0.0;  // faces may lean this far past vertical and count as facing the axis (degrees,
                                  // [0, 45], see overhang_sine(); 0 = exact height fields)
  const std::vector<std::uint8_t>* allowed_overhangs = nullptr;  // per face of the mesh passed: bit k set = the
                                  // face counts as facing both +-e_k (decompose --tolerance: its undercut is within
                                  // the tolerance, tolerance_allowances()); nullptr = none
  const std::vector<std::array<double, 3>>* overhang_floors = nullptr;  // with allowed_overhangs, per face and
                                  // dimension k: the allowance of bit k holds only in boxes whose base (min of x.d
                                  // over the box, d the direction along e_k the face faces away from) is >= this
                                  // (-inf: every box; see solid_index.h and tolerance_allowances.h); nullptr = every box

  Progress* progress = nullptr;  // stage reporting (nullptr = silent)
};

//! Result of resolve_overlaps().
struct ResolveResult {
  std::vector<HeightBox> ordered;         // carve order: ordered[0] is carved first
  int num_splits = 0;                     // boxes replaced by pieces to break cycles
  int num_trims = 0;                      // boxes trimmed (one face moved inward) to break cycles
  int num_dropped_pieces = 0;             // pieces left out (empty or surface-free blocks)
  std::size_t num_conflict_edges = 0;     // edges of the initial conflict graph
  std::size_t num_boxes_on_cycles = 0;    // boxes in non-trivial strongly connected components at the start
};

//! Orders (and where needed splits) height boxes for carving (thesis 4.3.3).
//! Block sizes for the order are the volumes of the boxes clipped to the
//! mesh's bounding box (deterministic, cheap; smaller first).
//! Deterministic and independent of the thread count.
//! \param mesh  closed, outward-oriented triangle mesh (canonical frame)
//! \param boxes valid height boxes (no triangle facing away from a box's axis
//!              meets its open interior), e.g. the output of select_cover
//! \return the boxes in carve order; for every i < j, solid ∩ (B_j \ B_i) is
//!         a valid height-field block
//! \throw InvalidArgumentError if a box is not valid or has non-finite or
//!        inverted coordinates.
//! \throw AlgorithmError if options.max_splits splits do not remove all cycles.
ResolveResult resolve_overlaps(const Mesh& mesh, std::vector<HeightBox> boxes, const ResolveOptions& options);

}  // namespace subfab
