// SPDX-License-Identifier: GPL-3.0-or-later
//! \file lazy_solid.h
//! Private: a block's exact inside test and surface distance tree, built on
//! first use, once, from any thread (the sampled lower and the surface upper
//! bounds of the fill deviation query only the blocks near their points).
#pragma once

#include <memory>
#include <mutex>

#include "geometry/solid_index.h"
#include "geometry/triangle_tree.h"
#include "subfab/mesh/mesh.h"

namespace subfab::detail {

struct LazySolid {
  std::once_flag once;
  std::unique_ptr<SolidIndex> index;     // exact inside/outside
  std::unique_ptr<TriangleTree> surface;  // its faces, distance queries ready
  //! Builds both for `m` on the first call; later calls return at once.
  void build(const Mesh& m) {
    std::call_once(once, [&] {
      index = std::make_unique<SolidIndex>(m);
      surface = std::make_unique<TriangleTree>(m);
      surface->accelerate_distance_queries();
    });
  }
};

}  // namespace subfab::detail
