// SPDX-License-Identifier: GPL-3.0-or-later
//! \file undercut_depth.h
//! Private estimate of how thick the material is that a 3-axis machine
//! leaves under a face leaning past vertical (issue 17: the fill of a
//! milled shape, thesis Section 4.3.5). A tool coming from +d cannot reach
//! below a face whose unit normal has n.d < 0; the material it leaves there
//! reaches down along -d until the surface (or the block's base) stops it.
//! Its thickness normal to the face, at a point p of the face, is the free
//! length L(p) along -d below p times |n.d|: the distance from the bottom
//! of that column to the face's plane.
//!
//! A heuristic, never a validity test: the columns are sampled at the
//! centroid and at three points near the corners (double-precision ray
//! casting, CGAL AABB tree), and the fill can reach farther than the face's
//! plane where the surface below recedes. The decisions that matter are
//! measured exactly afterwards (FillDeviationMeter).
#pragma once

#include <cstddef>
#include <memory>

#include "subfab/mesh/mesh.h"

namespace subfab::detail {

class UndercutDepth {
 public:
  //! Builds the ray-casting index over the mesh's faces (copies them).
  explicit UndercutDepth(const Mesh& mesh);
  ~UndercutDepth();
  UndercutDepth(const UndercutDepth&) = delete;
  UndercutDepth& operator=(const UndercutDepth&) = delete;

  //! Thickness of the material left under face `face` for the unit
  //! direction `d` (model units): 0 when the face faces d (n.d >= 0),
  //! else max over the samples of min(L, cap) x |n.d|, L the free length
  //! along -d to another face of the mesh. When cap x |n.d| <= limit the
  //! rays are not cast and that bound is returned (it is <= limit).
  //! Thread-safe.
  double depth(std::size_t face, const Vec3& d, double cap, double limit = 0.0) const;

  const Mesh& mesh() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace subfab::detail
