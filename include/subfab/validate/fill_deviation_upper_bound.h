// SPDX-License-Identifier: GPL-3.0-or-later
//! \file fill_deviation_upper_bound.h
//! A cheap, sound upper bound of the deviation FillDeviationMeter measures
//! exactly (measure_fill_deviation.h; issue 17, "validate takes no longer
//! than decompose"): validate's check 10 accepts a block on it and measures
//! in regions, with exact booleans, only the blocks it does not clear.
//!
//! With S the input solid, F_k the blocks that stick out of it and
//! P_k = closure(F_k \ S) their parts outside it (validate's check 4 makes
//! them), the model made is U = S ∪ (∪ F_k) and the deviation is the
//! symmetric Hausdorff distance between ∂U and ∂S. Every point that can
//! deviate lies on the surface of some P_k:
//!   - a point p of ∂U not on ∂S is not in S (else it would be on ∂S or
//!     inside U), so it lies in some F_k \ S ⊆ P_k, and on ∂P_k since
//!     int P_k ⊆ int U;
//!   - a point x of ∂S inside U (buried) has points outside S in every
//!     neighbourhood, all in U, so in some F_k \ S: x ∈ P_k; and points of S's
//!     interior near it, which are not in int P_k: x ∈ ∂P_k.
//! (Every other point of ∂U lies on ∂S and every other point of ∂S on ∂U:
//! distance 0.) So with T_k = sup over ∂P_k of d(., ∂S) and B_k = sup over
//! ∂P_k of d(., A) for any A ⊆ ∂U, the deviation is <= max_k max(T_k, B_k).
//!
//! A, the TARGETS: the faces of the parts that lie on ∂U for sure. The
//! exact part (check 4's corefinement, before its vertices are rounded to
//! doubles) has all its intersections with ∂S as edges, so each of its faces
//! either lies on ∂S or has its interior outside the closed solid S; which,
//! check 4 decides exactly (OutsidePart::on_input). A face of the second
//! kind, a piece of ∂F_k, lies on ∂U when it also misses every other F_j
//! (then the points just outside it are in no F_j and not in S). Decided on
//! the rounded face with a margin `contact` = 1e-10 x the largest coordinate
//! (far above the rounding): the face farther than `contact` from every other
//! F_j's faces (closest points of triangle pairs) and its centroid outside
//! every F_j (exact). A face that fails is not a target, which only makes
//! the bound larger. Distances: CGAL's bounded-error one-sided Hausdorff
//! distance (within `error`), plus 16 ulps of the largest coordinate for the
//! rounding of each rounded mesh involved (rounding_slack()).
//!
//! How tight: on the thin layers a tolerance leaves (a box plane a little
//! outside the input, a filled undercut), T_k is the exact measure's
//! "sticks out" and B_k the layer's thickness over the buried input.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! The bound of one block (model units, infinity when not bounded; the
//! Hausdorff error bound and the rounding included: true upper bounds).
struct FillDeviationUpperBound {
  double to_input = std::numeric_limits<double>::infinity();    // >= sup over ∂P_k of the distance to ∂S
  double from_input = std::numeric_limits<double>::infinity();  // >= sup over ∂P_k of the distance to the targets
  double bound() const { return to_input > from_input ? to_input : from_input; }
};

struct FillDeviationUpperBounds {
  std::vector<FillDeviationUpperBound> blocks;  // one per filled block
  std::size_t target_faces = 0;                 // part faces taken as targets (on ∂U for sure)
  std::size_t part_faces = 0;                   // part faces in all
};

//! Options of fill_deviation_upper_bounds().
struct FillDeviationUpperBoundOptions {
  double error = 0.0;  // error bound of the Hausdorff distances (model units, > 0)
  double stop = std::numeric_limits<double>::infinity();  // model units, the tolerance the bound is for: a
                       // block's distance to ∂S is first bounded over the parts' faces on ∂S (a part of ∂S,
                       // near: CGAL refines a face lying just off a differently triangulated surface down to
                       // the error, so the whole of ∂S costs more), over the whole of ∂S only when that
                       // exceeds `stop`; +infinity: the parts' faces only
  double coarse_fraction = 0.0;  // >= 0: first pass within max(error, this x stop), again within `error` the
                                 // blocks whose bound then exceeds `stop` (a block far below it gets a looser
                                 // bound, fast: hu's part 10 s at 2 % of T, 1.6 s at 25 %); 0: one pass
};

//! A filled block's part outside S, as validate's check 4 makes it.
struct FillPart {
  const Mesh* faces = nullptr;                 // the faces of closure(F_k \ S)
  const std::vector<char>* on_input = nullptr;  // per face: 1 when it lies on ∂S (exact), 0 when its interior is outside S
};

//! The bounds of the file comment, per filled block.
//! \param solid  S: closed, outward-oriented, self-intersection-free solid
//! \param filled every block that sticks out of S (each is "another" for the rest)
//! \param parts  per filled block, the faces bounding closure(F_k \ S) (a closed mesh or a triangle soup,
//!               vertices rounded once from exact points: validate's check 4) and which of them lie on ∂S;
//!               faces nullptr: not bounded
//! \param which  per filled block, whether to bound it (empty: all); every part is a target candidate anyway
//! \return deterministic whatever the thread count
//! \throw InvalidArgumentError on mismatched sizes, error <= 0 or a negative coarse fraction
FillDeviationUpperBounds fill_deviation_upper_bounds(const Mesh& solid, const std::vector<const Mesh*>& filled,
                                                     const std::vector<FillPart>& parts,
                                                     const FillDeviationUpperBoundOptions& options,
                                                     const std::vector<char>& which = {});

}  // namespace subfab
