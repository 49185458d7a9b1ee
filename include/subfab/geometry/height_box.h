// SPDX-License-Identifier: GPL-3.0-or-later
//! \file height_box.h
//! The value types the decomposition stages pass to each other (thesis
//! Section 4.3): an axis-aligned box with a milling direction. The block it
//! stands for is the input solid intersected with the box (Section 4.2).
#pragma once

#include <algorithm>
#include <vector>

#include "subfab/geometry/axis.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Closed axis-aligned box [min, max] (model units, canonical frame).
struct Box3 {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();

  Vec3 size() const { return max - min; }
  double volume() const {
    const Vec3 s = size();
    return (s.array() > 0).all() ? s.prod() : 0.0;
  }
  bool contains(const Vec3& p) const {
    return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
  }
  //! True when the interiors intersect (touching faces do not count).
  bool overlaps(const Box3& o) const {
    return (min.array() < o.max.array()).all() && (o.min.array() < max.array()).all();
  }
};

//! A candidate height-field block: (input solid) intersected with `box`,
//! milled along `axis`. Valid when no input triangle facing away from the
//! axis (n.d < 0) meets the interior of the box (thesis Section 4.3.2).
struct HeightBox {
  Box3 box;
  Axis axis = Axis::PosZ;
  int seed_face = -1;  // triangle the box was grown from (-1: none)
};

//! True when a box milled along `axis` respects the size limits of issue 3:
//! its extent along the axis is at most min(max_height, machine.z()), and its
//! two other extents fit machine.x() x machine.y() in either order (model
//! units; infinite values mean no limit).
inline bool box_fits_limits(const Box3& b, Axis axis, double max_height, const Vec3& machine) {
  const int ad = axis_dimension(axis);
  const int u = (ad + 1) % 3, v = (ad + 2) % 3;
  const double h = b.max[ad] - b.min[ad], eu = b.max[u] - b.min[u], ev = b.max[v] - b.min[v];
  if (h > std::min(max_height, machine.z())) return false;
  return (eu <= machine.x() && ev <= machine.y()) || (eu <= machine.y() && ev <= machine.x());
}

}  // namespace subfab
