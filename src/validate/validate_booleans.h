// SPDX-License-Identifier: GPL-3.0-or-later
//! \file validate_booleans.h
//! Private: variants of the exact booleans of validate_booleans.cpp for the
//! milled-shape measures, which report volumes to the last digit and must
//! not depend on the thread count.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! Why the exact booleans refuse the closed mesh `m` ("has N degenerate
//! (zero-area) faces; ..." or, with `whole_surface`, "intersects itself (N
//! pairs of faces); ..."), or empty when they accept it (exact checks).
std::string boolean_input_defect(const Mesh& m, bool whole_surface);

//! blocks_overlap() with the result's volume evaluated exactly (then
//! rounded once), so independent of how the corefinement triangulated it
//! (which depends on heap addresses, hence on the thread that ran it).
double exact_blocks_overlap(const Mesh& a, const Mesh& b);

//! exact_blocks_overlap() when a ∩ b is known to lie in the closed box
//! `within` up to a zero volume (two milled shapes whose carved blocks do
//! not overlap: the boxes of their fills, fill_columns()). Both blocks are
//! clipped near `within` before the boolean: the same volume, found from
//! fewer faces (their shared cut faces away from the fills left out).
double exact_blocks_overlap(const Mesh& a, const Mesh& b, const BoundingBox& within);

//! volume_outside() with the volume evaluated exactly, as exact_blocks_overlap().
double exact_volume_outside(const Mesh& block, const Mesh& solid);

//! What of a block lies outside the input solid (validate's check 4, and
//! the part check 10 measures).
struct OutsidePart {
  double volume = 0.0;       // vol(block \ solid): as volume_outside() (rounded coordinates), or with
                             // `boundary`, exactly from its faces
  std::optional<Mesh> mesh;  // block \ solid (closed, rounded to doubles) when the local boolean gave it
  //! Without `mesh` (CGAL's difference is not a 2-manifold: the part touches
  //! itself along an edge or at a point): the faces bounding block \ solid,
  //! a triangle soup (difference_surface(), vertices shared by exact
  //! position, rounded to doubles), when that classification succeeded.
  std::optional<Mesh> boundary;
  //! Per face of `mesh` or `boundary`: 1 when it lies on the solid's surface
  //! (a piece of the input's surface the block covers, or of the block's
  //! surface lying in it), 0 when it is a piece of the block's surface whose
  //! interior lies outside the closed solid; decided exactly, on the exact
  //! faces before their rounding (a corefined face lies on the solid's
  //! surface iff its centroid does). fill_deviation_upper_bound.h needs it.
  std::vector<char> on_input;
  //! The part's faces: `mesh`, else `boundary`, else nullptr.
  const Mesh* faces() const { return mesh ? &*mesh : boundary ? &*boundary : nullptr; }
};

//! volume_outside() that also gives the part outside: block \\ solid by
//! the same exact corefinement, run in a deterministic arena (the same
//! triangulation whatever the thread). Where it cannot give a 2-manifold,
//! falls back to volume_outside() (intersection, Nef), without `mesh` but
//! with `boundary` (the faces of the part, for check 10's cover).
//! (Clipping the input to the block's box first, with clip_solid_to_box(),
//! was tried: no faster on airplane, and a segfault inside CGAL on kitten.)
//! \throw AlgorithmError as volume_outside()
//! `within`, when given: an open box known to hold block \\ solid (a
//! milled shape's fill boxes, widened): the block is clipped to it first
//! (exactly), so the boolean sees only the faces near the fill; the same
//! part. It must not share a plane with a face of the block or the solid
//! (widen the fill's boxes by a margin).
OutsidePart outside_part(const Mesh& block, const Mesh& solid, const BoundingBox* within = nullptr);

}  // namespace subfab::detail
