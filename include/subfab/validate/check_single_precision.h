// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_single_precision.h
//! Does a mesh stay a solid once written in single precision (binary STL
//! stores float32 coordinates)? Issue 17, "no slivers": a block thinner than
//! float32's resolution collapses or crosses itself when rounded.
#pragma once

#include <cstddef>

#include "subfab/mesh/mesh.h"
#include "subfab/validate/validate_decomposition.h"

namespace subfab {

//! Result of check_single_precision().
struct SinglePrecisionReport {
  std::size_t num_welded = 0;             // vertices that the rounding made coincide (welded, as STL readers do)
  SolidReport solid;                      // check_closed_solid() of the rounded, welded mesh
  std::size_t num_self_intersections = 0; // pairs of its faces that intersect (check_self_intersections())
  bool ok() const { return solid.ok() && solid.num_degenerate_faces == 0 && num_self_intersections == 0; }
};

//! The mesh with every coordinate rounded to float32 (round to nearest), as
//! a binary STL stores it; `num_welded` receives how many vertices then
//! coincide with an earlier one (they are welded, faces keep their order).
Mesh round_to_single_precision(const Mesh& mesh, std::size_t* num_welded = nullptr);

//! Rounds `mesh` to float32, welds coinciding vertices and checks that the
//! result is a closed, oriented 2-manifold with positive volume, no
//! zero-area face and no self-intersection (exact predicates). A mesh whose
//! coordinates are already floats (read from an STL) is checked as is.
SinglePrecisionReport check_single_precision(const Mesh& mesh);

}  // namespace subfab
