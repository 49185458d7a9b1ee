// SPDX-License-Identifier: GPL-3.0-or-later
//! \file hausdorff_distance.h
//! Private: symmetric Hausdorff distance between two triangle meshes,
//! estimated on deterministic samples of both surfaces.
#pragma once

#include <cstddef>
#include <memory>

#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! max(sup_{a in A} d(a, B), sup_{b in B} d(b, A)) over samples: every vertex
//! and a regular barycentric grid on each triangle, fine enough that about
//! `samples_per_mesh` points cover each surface (model units).
double hausdorff_distance(const Mesh& a, const Mesh& b, std::size_t samples_per_mesh = 200000);

//! Distance from a point to a triangle mesh's surface (AABB tree), reusable.
class SurfaceDistance {
 public:
  explicit SurfaceDistance(const Mesh& mesh);
  ~SurfaceDistance();
  SurfaceDistance(const SurfaceDistance&) = delete;
  SurfaceDistance& operator=(const SurfaceDistance&) = delete;
  double operator()(const Vec3& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace subfab::detail
