// SPDX-License-Identifier: GPL-3.0-or-later
//! \file refine_mesh.h
//! Local one-to-four refinement of chosen triangles, keeping the mesh
//! conforming (thesis Section 4.3.5, "Initialization constraints": when a
//! triangle is larger than the local feature size its bounding box cannot be
//! a valid height-field box; splitting it makes room).
//!
//! Outline (red-green refinement):
//!   1. every edge of a chosen triangle gets a midpoint;
//!   2. a triangle with two or three split edges gets all three split
//!      (repeat until stable), so the result has only 1-to-4 and 1-to-2 splits;
//!   3. 1-to-4 split of triangles with three split edges, 1-to-2 split of
//!      triangles with one (towards the opposite vertex), others unchanged.
//! The result stays closed, manifold and consistently oriented when the
//! input is, and describes the same surface (up to the rounding of the
//! midpoints (a + b) / 2, at most half an ulp per coordinate).
#pragma once

#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! Result of refine_mesh().
struct RefineResult {
  Mesh mesh;                    // refined mesh: input vertices first (same ids), then midpoints
  std::vector<int> parent;      // per face of `mesh`: the input face it lies in
  int num_split_1to4 = 0;       // input faces split into four
  int num_split_1to2 = 0;       // input faces split into two (conformity)
};

//! Splits the listed faces one-to-four and their neighbours as needed to
//! stay conforming. Face f of the input keeps id f (its first child); the
//! other children are appended in input-face order. Deterministic.
//! \param mesh   #V vertices, #F faces
//! \param faces  ids of faces to split (any order, duplicates allowed)
//! \throw InvalidArgumentError if a face id is out of range.
RefineResult refine_mesh(const Mesh& mesh, const std::vector<int>& faces);

}  // namespace subfab
