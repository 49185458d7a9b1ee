// SPDX-License-Identifier: GPL-3.0-or-later
//! \file surface_projector.h
//! Private: closest points and ray hits on the input surface (CGAL AABB tree),
//! for placing the boundary of the hexahedral mesh (thesis D.6).
#pragma once

#include <memory>
#include <optional>

#include "subfab/mesh/mesh.h"

namespace subfab::detail {

class SurfaceProjector {
 public:
  explicit SurfaceProjector(const Mesh& surface);
  ~SurfaceProjector();
  SurfaceProjector(const SurfaceProjector&) = delete;
  SurfaceProjector& operator=(const SurfaceProjector&) = delete;

  //! The point of the surface closest to p, and the unit normal of its face.
  Vec3 closest_point(const Vec3& p, Vec3* normal = nullptr) const;
  //! The first point where the ray from `origin` along `direction` meets the
  //! surface, if any.
  std::optional<Vec3> first_hit(const Vec3& origin, const Vec3& direction) const;
  //! Whether p is inside the closed surface: exact (SolidIndex::is_inside,
  //! which needs a closed, oriented, self-intersection-free surface).
  bool inside(const Vec3& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace subfab::detail
