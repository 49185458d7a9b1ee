// SPDX-License-Identifier: GPL-3.0-or-later
//! \file pinch_points.h
//! Private: where a carved piece touches itself, and the axis-aligned cuts
//! through those points (thesis Section 4.3.3, carving). Where the solid
//! surface touches a face of a box region from inside (at a vertex, or along
//! an edge lying in the face) the solid there has zero thickness; carving
//! cuts the region by an axis-aligned plane through the contact so that each
//! block is a 2-manifold (carve_box_region.h), and when no such plane is
//! left, reports the region faces holding the contact (contact_points(),
//! on_box_face()) for ContactMover (contact_mover.h). Only .cpp files
//! include it.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "geometry/exact_mesh.h"
#include "subfab/geometry/height_box.h"

namespace subfab::detail {

//! Extra planes that cut a box region, per axis (sorted, each strictly
//! inside the box): the pieces on either side become separate blocks.
using Cuts = std::array<std::vector<double>, 3>;

//! Is v one of the planes of `cuts` across axis k (sorted per axis)?
bool is_cut(const Cuts& cuts, int k, double v);

//! The points where a connected piece of `mesh` touches itself: two of its
//! vertices at the same exact point. That happens where the solid surface
//! touches a face of the region from inside (at a vertex, or along an edge
//! lying in the face): the solid there is not a 2-manifold (its thickness
//! drops to zero), and split_soup() (clip_solid_to_box.cpp) or CGAL can
//! only give the point one vertex per umbrella, so the block would touch
//! itself. Sorted, unique.
std::vector<ExactPoint> pinch_points(ExactMesh& mesh);

//! The contact at pinch point p of `mesh`: p and the far ends of the edges
//! that the umbrellas at p share geometrically (two vertices at p joined to
//! two vertices at one point q: the surface touches the region along the
//! segment pq). Sorted, unique, p included.
std::vector<ExactPoint> contact_points(const ExactMesh& mesh, const ExactPoint& p);

//! Is p on the face of `b` in plane x_k = b.min[k] or b.max[k] (closed)?
bool on_box_face(const ExactPoint& p, const Box3& b, int k);

//! Adds, for each pinch point, one plane through it to `cuts`: the first
//! axis along which the point has a double coordinate strictly inside `box`,
//! not cut yet, and the point lies on no face of a hole across that axis (a
//! plane across the region faces the surface touches splits the
//! zero-thickness point between two blocks, each a 2-manifold there).
//! Returns false when no point got one; `num_added` counts the planes added.
bool add_pinch_cuts(const std::vector<ExactPoint>& pinches, const Box3& box, const std::vector<Box3>& holes,
                    Cuts& cuts, std::size_t& num_added);

}  // namespace subfab::detail
