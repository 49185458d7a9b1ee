// SPDX-License-Identifier: GPL-3.0-or-later
//! \file union_surface.h
//! Private: the boundary of a union (or a difference) of closed solids, exactly, when the
//! solids may touch each other along an edge or at a point (issue 17: the
//! fill-deviation measure, measure_fill_deviation.h, needs the surface of
//! the input ∪ the filled blocks near a fill; CGAL's union refuses to build
//! it when the result is not a 2-manifold). The boundary is returned as a
//! list of faces of the (corefined) operands: a triangle soup, possibly
//! non-manifold, which is all a distance measure needs. Only .cpp files
//! include it (CGAL stays out of public headers).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "geometry/exact_mesh.h"

namespace subfab::detail {

//! The faces of ∂(O_1 ∪ ... ∪ O_m), exactly, for closed, outward-oriented,
//! self-intersection-free triangle meshes O_i that may touch one another
//! anywhere (along an edge, at a point, face to face) and may overlap:
//!   1. every pair of operands whose boxes meet is corefined (CGAL
//!      PMP::corefine, exact kernel: the intersection curves become edges of
//!      both; no 2-manifold output is required), so afterwards every face of
//!      O_a lies wholly inside, wholly outside or wholly on ∂O_b. Each pair
//!      refines meshes that earlier pairs refined (points constructed from
//!      constructed points, 300-1000 bits), so exact work on refined meshes
//!      is kept to the corefinements themselves: self-intersections are
//!      checked once on the given operands (CGAL's check inside every
//!      corefinement, on refined meshes, was a third of the overlay's time:
//!      bench/RESULTS.md "fillfast");
//!   2. a face f of O_a is on the boundary of the union iff its interior is
//!      outside every other operand: one point of its interior (its
//!      centroid, exact) is classified against each O_b whose box holds it
//!      (CGAL Side_of_triangle_mesh, exact kernel, on O_b as given: the side
//!      of a point does not depend on how O_b is refined): inside drops f; on ∂O_b
//!      (f lies in a face g of O_b, coplanar) keeps f only when g faces the
//!      same way and a < b (one copy of a shared face; two solids meeting
//!      face to face along opposite faces have no boundary there). Faces
//!      joined across an edge that cannot lie on another operand (not both
//!      its ends at vertices of one) lie on the same side of every operand:
//!      one face per such patch is classified.
//! Measured on pieces of the bunny (bench/RESULTS.md, issue 17): the same
//! distances as CGAL's unions to 5 digits, 1.6-2.8x their time: the unions
//! stay the fast path where they work.
//! \param operands the solids; corefined in place
//! \return the kept faces as (operand, face) pairs, in operand and face
//!         order (deterministic); false when an operand has two vertices at
//!         one exact point (CGAL's corefinement precondition) or a face lies
//!         on another operand's boundary without a coplanar face under it
//!         (cannot happen after a correct corefinement: reported, not guessed)
//! \throw CGAL's Self_intersection_exception when an operand self-intersects
//!        (run it in an arena, see deterministic_arena.h)
bool union_surface(std::vector<ExactMesh>& operands, std::vector<std::pair<std::size_t, FaceIndex>>& kept);

//! The faces of ∂(O_0 \ O_1), exactly, for two closed, outward-oriented,
//! self-intersection-free operands that CGAL has already corefined with each
//! other (`corefined`: a CGAL difference that refused to output a result
//! that is not a 2-manifold leaves its operands so: validate's check 4, a
//! block's part outside the input touching itself along an edge), by
//! union_surface()'s classification (step 2) against the operands as
//! `given` before: a face of O_0 is kept when it lies outside O_1, or on ∂O_1
//! in a face of O_1 facing the other way (O_0 lies outside O_1 there); a face
//! of O_1 when it lies inside O_0 (kept as O_1 orients it: reverse it for
//! the difference's outward orientation). Check 10 measures the deviation
//! only where that part is.
//! \return as union_surface()
//! \throw InvalidArgumentError unless there are two operands of each
bool difference_surface(const std::vector<ExactMesh>& corefined, const std::vector<ExactMesh>& given,
                        std::vector<std::pair<std::size_t, FaceIndex>>& kept);

}  // namespace subfab::detail
