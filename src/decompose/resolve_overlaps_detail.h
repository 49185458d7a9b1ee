// SPDX-License-Identifier: GPL-3.0-or-later
//! \file resolve_overlaps_detail.h
//! The exact geometric tests of overlap resolution (thesis Section 4.3.3),
//! and an entry point that reuses a SolidIndex (the pipeline builds one).
#pragma once

#include <functional>

#include "decompose/order_boxes.h"
#include "geometry/solid_index.h"
#include "subfab/decompose/resolve_overlaps.h"

namespace subfab::detail {

//! Exact: is solid ∩ (second \ first) NOT a valid height-field block
//! (edge first -> second of the conflict graph)? `second` must be valid.
//! True iff conflict_region(first, second) exists and the solid's interior
//! meets that open box: some triangle meets it (then solid interior lies on
//! one side of the triangle, inside the open box), or no triangle does and
//! its min corner, perturbed into the box, is inside.
bool carving_conflict(const SolidIndex& index, const HeightBox& first, const HeightBox& second);

//! Trims that break the conflict edge first -> second (empty if there is no
//! such edge): for each of the 12 faces of the two boxes, the least inward
//! move (bisection over doubles, the result checked exactly) after which the
//! edge is gone, kept when `keeps_surface(old, trimmed)` agrees. `removed`
//! is size(old) - size(trimmed). Trimmed boxes are sub-boxes: still valid.
std::vector<BoxTrim> conflict_trims(const SolidIndex& index, const HeightBox& first, const HeightBox& second,
                                    const std::function<double(const HeightBox&)>& size,
                                    const std::function<bool(const HeightBox&, const HeightBox&)>& keeps_surface);

//! Exact: may a piece of a split be left out without losing surface? True
//! when its block has no volume (the solid's interior misses the open piece),
//! when no triangle touches the closed piece (empty or an interior chunk), or
//! when every triangle touching the closed piece is covered (faces_covered)
//! by another live box, according to `covered_elsewhere`: then every surface
//! point of the piece has the solid next to it inside that other box.
bool split_piece_droppable(const SolidIndex& index, const HeightBox& piece,
                           const std::function<bool(int face)>& covered_elsewhere);

//! resolve_overlaps() on a prebuilt index (same contract).
ResolveResult resolve_overlaps(const SolidIndex& index, std::vector<HeightBox> boxes, const ResolveOptions& options);

}  // namespace subfab::detail
