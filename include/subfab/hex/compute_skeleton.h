// SPDX-License-Identifier: GPL-3.0-or-later
//! \file compute_skeleton.h
//! The curve-skeleton of a closed solid, computed automatically (thesis
//! Appendix D.3 needs one; the thesis used external tools and edited some by
//! hand, subfab does both steps itself):
//!   1. CGAL's mean-curvature-flow skeleton (Tagliasacchi et al. 2012,
//!      CGAL::Mean_curvature_flow_skeletonization, default parameters);
//!   2. the radius of each node: the mean distance from the node to the
//!      surface vertices that contracted onto it (its correspondents); the
//!      distance to the surface for a node with none;
//!   3. clean_skeleton() (see clean_skeleton.h), unless disabled.
//! Deterministic: no randomness, serial.
#pragma once

#include "subfab/core/progress.h"
#include "subfab/hex/clean_skeleton.h"
#include "subfab/hex/skeleton.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

struct ComputeSkeletonOptions {
  bool clean = true;                  // run clean_skeleton() on the raw skeleton
  CleanSkeletonOptions clean_options;  // its options
  Progress* progress = nullptr;       // stage reporting (nullptr = silent)
};

//! Raw and cleaned skeleton sizes, for reports.
struct ComputeSkeletonReport {
  std::size_t raw_nodes = 0;
  std::size_t raw_edges = 0;
  CleanSkeletonReport clean;
};

//! The curve-skeleton of `mesh`, a closed, outward-oriented, manifold solid.
//! \throw AlgorithmError when the flow produces no skeleton (empty result).
Skeleton compute_skeleton(const Mesh& mesh, const ComputeSkeletonOptions& options = {},
                          ComputeSkeletonReport* report = nullptr);

}  // namespace subfab
