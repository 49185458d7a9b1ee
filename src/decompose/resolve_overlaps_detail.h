// SPDX-License-Identifier: GPL-3.0-or-later
//! \file resolve_overlaps_detail.h
//! The exact geometric tests of overlap resolution (thesis Section 4.3.3),
//! and an entry point that reuses a SolidIndex (the pipeline builds one).
#pragma once

#include "decompose/solid_index.h"
#include "subfab/decompose/resolve_overlaps.h"

namespace subfab::detail {

//! Exact: is solid ∩ (second \ first) NOT a valid height-field block
//! (edge first -> second of the conflict graph)? `second` must be valid.
//! True iff conflict_region(first, second) exists and the solid's interior
//! meets that open box: some triangle meets it (then solid interior lies on
//! one side of the triangle, inside the open box), or no triangle does and
//! its min corner, perturbed into the box, is inside.
bool carving_conflict(const SolidIndex& index, const HeightBox& first, const HeightBox& second);

//! Exact: may a piece of a split be left out without losing surface? True
//! when no triangle meets its open interior and either it lies outside the
//! solid (its block is empty) or no triangle touches the closed piece (its
//! block is an interior chunk that touches no surface).
bool split_piece_droppable(const SolidIndex& index, const HeightBox& piece);

//! resolve_overlaps() on a prebuilt index (same contract).
ResolveResult resolve_overlaps(const SolidIndex& index, std::vector<HeightBox> boxes, const ResolveOptions& options);

}  // namespace subfab::detail
