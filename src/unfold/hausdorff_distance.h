// SPDX-License-Identifier: GPL-3.0-or-later
//! \file hausdorff_distance.h
//! Private: symmetric Hausdorff distance between two triangle meshes,
//! estimated on deterministic samples of both surfaces.
#pragma once

#include <cstddef>

#include "subfab/mesh/mesh.h"

namespace subfab::unfold_detail {

//! max(sup_{a in A} d(a, B), sup_{b in B} d(b, A)) over samples: every vertex
//! and a regular barycentric grid on each triangle, fine enough that about
//! `samples_per_mesh` points cover each surface (model units).
double hausdorff_distance(const Mesh& a, const Mesh& b, std::size_t samples_per_mesh = 200000);

}  // namespace subfab::unfold_detail
