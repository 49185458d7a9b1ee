// SPDX-License-Identifier: GPL-3.0-or-later
//! \file polygons_overlap.h
//! Private: exact test of whether the interiors of two planar polygons with
//! holes overlap (used to keep the facets of a net apart, Section 3.3.3).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace subfab::unfold_detail {

//! Polygon with holes: loops[0] counter-clockwise, holes clockwise; the
//! interior is on the left of every edge.
struct Polygon2 {
  std::vector<std::vector<Eigen::Vector2d>> loops;
  Eigen::Vector2d lo{0, 0}, hi{0, 0};  // bounding box
};

//! Sets the bounding box of p from its loops.
void update_box(Polygon2& p);

//! True when the interiors of a and b intersect. Decided exactly from the
//! double coordinates (exact orientation predicates; exact rationals for
//! midpoints): boundaries that touch or run along each other in opposite
//! directions (a fold edge) do not count.
bool interiors_overlap(const Polygon2& a, const Polygon2& b);

}  // namespace subfab::unfold_detail
