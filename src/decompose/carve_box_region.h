// SPDX-License-Identifier: GPL-3.0-or-later
//! \file carve_box_region.h
//! Private: carving one box of the carving order (thesis Section 4.3.3,
//! the Boolean stage of carve_blocks()): solid ∩ (B_i \ (B_0 ∪ ... ∪
//! B_{i-1})) as exact pieces, cut through the points where the surface
//! touches the region from inside (pinch_points.h), split into connected
//! pieces, those touching the input surface rounded to doubles. Also the
//! per-box work product that carve_blocks() collects and ContactMover
//! (contact_mover.h) acts on. Only .cpp files include it.
#pragma once

#include <cstddef>
#include <tuple>
#include <vector>

#include "geometry/exact_mesh.h"
#include "geometry/solid_index.h"
#include "subfab/geometry/height_box.h"
#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! A face of a box of the carving order: box `box`, plane x_k = min[k]
//! (side -1) or max[k] (side +1).
struct BoxFace {
  std::size_t box = 0;
  int k = 0;
  int side = 0;
  auto key() const { return std::make_tuple(box, k, side); }
  bool operator<(const BoxFace& o) const { return key() < o.key(); }
  bool operator==(const BoxFace& o) const { return key() == o.key(); }
};

//! A contact no axis-aligned cut separated: the faces of the region (of the
//! box itself or of an earlier box) that hold the whole contact.
struct Contact {
  std::vector<BoxFace> faces;
};

//! The per-box work product.
struct BoxPieces {
  std::vector<Mesh> pieces;
  std::size_t num_dropped = 0;
  bool split_region = false;
  std::size_t num_pinch_cuts = 0;  // planes cut through pinch points
  std::size_t num_unresolved_pinches = 0;  // pinch points no cut separated
  std::vector<Contact> contacts;   // the region faces holding them
  detail::RoundingReport rounding;
};

//! The pieces of box i of `boxes` (the carving order), computed in a private
//! arena (see deterministic_arena.h) so that the result does not depend on
//! the thread that runs it. The region of box i is the box minus the earlier
//! boxes (holes) that overlap it; no pieces when an earlier box contains it.
//! `index` is the SolidIndex of `solid`. Thread-safe.
//! \throw AlgorithmError naming box i when an exact step fails.
BoxPieces carve_box_region(const Mesh& solid, const SolidIndex& index, const std::vector<HeightBox>& boxes,
                           std::size_t i);

}  // namespace subfab::detail
