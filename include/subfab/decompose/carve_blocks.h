// SPDX-License-Identifier: GPL-3.0-or-later
//! \file carve_blocks.h
//! Carving (thesis Sections 4.2 and 4.3.3, the Boolean stage "B" of
//! Table 4.1): turns the ordered height boxes into solid blocks,
//!
//!   block_i = solid ∩ (B_i \ (B_0 ∪ ... ∪ B_{i-1})),
//!
//! computed exactly (CGAL corefinement on an exact kernel), then split into
//! connected pieces; pieces that touch no part of the input surface are
//! dropped (the interior may stay empty, thesis 4.1).
//!
//! Outline:
//!   for every box i (in parallel, each independent of the others):
//!     P = clip(solid, B_i)                      exact, closed
//!     for every earlier box j whose interior meets B_i: P = P \ B_j
//!       (if a difference would be non-manifold, B_i \ ∪ B_j is cut into
//!        disjoint boxes instead and each is clipped separately)
//!     while a piece of P touches itself (the surface touches a face of the
//!       region from inside: zero thickness), cut the region by an
//!       axis-aligned plane through each contact and carve each part again
//!     split P into connected pieces, keep those touching the input surface
//!   for a contact no such plane separates (e.g. a segment slanted in the
//!     face), in box order: move the region face holding it (of the box or
//!     of an earlier box) off it by contact_move x diagonal, outward when the
//!     box stays exactly valid, else inward when every triangle stays held
//!     by some box; carve the changed regions again (max_contact_rounds)
//!   round every kept piece to doubles, in box order.
#pragma once

#include <array>
#include <cstdint>

#include <cstddef>
#include <limits>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/geometry/axis.h"
#include "subfab/geometry/height_box.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! One solid block of the decomposition, in the canonical frame.
struct Block {
  Mesh mesh;              // closed, outward-oriented triangle mesh (model units)
  Axis axis = Axis::PosZ; // milling direction: the base faces -axis
  int source_box = -1;    // index of the ordered box it was carved from
};

//! Options of carve_blocks().
struct CarveOptions {
  double contact_move = 1e-6;     // first distance a box face is moved off a contact no axis-aligned
                                  // cut separates, as a fraction of the solid's bounding-box diagonal
                                  // (x10 each time the same face is moved again, at most 3 times); > 0
  int max_contact_rounds = 4;     // rounds of such moves, each followed by carving the changed
                                  // regions again (0: never move a face); >= 0
  double max_height = std::numeric_limits<double>::infinity();  // a moved box stays within this
                                  // extent along its axis (model units, see box_fits_limits)
  Vec3 machine_size = Vec3::Constant(std::numeric_limits<double>::infinity());  // and fits this work
                                  // volume X, Y, Z (model units, Z along the axis)
  double max_overhang_deg = 0.0;  // faces may lean this far past vertical and count as facing the axis (degrees,
                                  // [0, 45], see overhang_sine(); 0 = exact height fields)
  const std::vector<std::uint8_t>* allowed_overhangs = nullptr;  // per face of the mesh passed: bit k set = the
                                  // face counts as facing both +-e_k (decompose --tolerance: its undercut is within
                                  // the tolerance, tolerance_allowances()); nullptr = none
  const std::vector<std::array<double, 3>>* overhang_floors = nullptr;  // with allowed_overhangs, per face and
                                  // dimension k: the allowance of bit k holds only in boxes whose base (min of x.d
                                  // over the box, d the direction along e_k the face faces away from) is >= this
                                  // (-inf: every box; see solid_index.h and tolerance_allowances.h); nullptr = every box
  Progress* progress = nullptr;   // stage progress and warnings (nullptr: silent)
};

//! What carve_blocks() produced and what it had to do.
struct CarveResult {
  std::vector<Block> blocks;             // ordered by source box, then by piece
  std::size_t num_dropped_pieces = 0;    // pieces touching no input surface (interior)
  std::size_t num_split_regions = 0;     // boxes whose region had to be cut into disjoint boxes
  std::size_t num_pinched_regions = 0;   // boxes whose region the surface touches from inside (zero
                                         // thickness at a point or edge), cut through the contact
  std::size_t num_pinch_cuts = 0;        // planes cut through such contacts, summed over boxes
  std::size_t num_moved_faces = 0;       // box faces moved off contacts no axis-aligned cut separated
  std::size_t num_unresolved_pinches = 0;  // contacts neither a cut nor a face move separated
                                           // (the block there touches itself; finalize rejects it)
  std::size_t num_degenerate_faces = 0;  // faces that became zero-area when rounded to doubles
  std::size_t num_flipped_faces = 0;     // faces whose normal flipped when rounded to doubles
};

//! Carves the blocks of `ordered_boxes` out of `solid`.
//! \param solid          closed, outward-oriented, self-intersection-free mesh
//!                       (canonical frame, the mesh the boxes were grown on)
//! \param ordered_boxes  the boxes in carving order (earlier boxes take
//!                       precedence where they overlap), canonical frame
//! \return the blocks (double coordinates; each a closed, oriented 2-manifold
//!         piece of one region), ordered by box then by piece.
//! \throw AlgorithmError when an exact boolean cannot produce a manifold piece.
CarveResult carve_blocks(const Mesh& solid, const std::vector<HeightBox>& ordered_boxes,
                         const CarveOptions& options = {});

}  // namespace subfab
