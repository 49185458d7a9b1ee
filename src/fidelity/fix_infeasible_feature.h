// SPDX-License-Identifier: GPL-3.0-or-later
//! \file fix_infeasible_feature.h
//! Private: stage A of repair_infeasible_features() (thesis Section 4.3.5,
//! local version), the local edits of one infeasible feature, cheapest
//! first: splits of its faces along the coordinate planes through a vertex
//! (no deviation), single-vertex moves (candidate positions incl. the nearest
//! ones where the vertex's star faces one axis), Laplacian smoothing of a
//! small disc, and the chamfer of a sharp ridge vertex. Each edit is kept
//! only if the exact test then finds strictly fewer features (so the repair
//! moves towards feasibility and terminates). The driver (refinement of the
//! stars no edit fixed, stage B, the report) is in
//! repair_infeasible_features.cpp.
#pragma once

#include <vector>

#include "subfab/fidelity/find_infeasible_features.h"
#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! The mesh being repaired and `reference`: the same faces, each vertex at its
//! point of the input surface (every reference face lies in one input face),
//! so max |vertex - reference| bounds the Hausdorff distance to the input.
struct RepairWork {
  Mesh mesh;
  Mesh reference;
  //! A vertex move changes no coordinate by this little or less (model
  //! units; 0: off): such a change is the rounding noise of the candidate
  //! formulas (a projection onto a plane, a centroid of equal coordinates),
  //! and applying it moves a vertex off the axis-aligned plane it shared with
  //! its neighbours (anchor.off: 8.7e-13 off y = 0.0960186, which left a
  //! block with a sheet that thin, not a solid once written in float32).
  double coordinate_noise = 0.0;
};

//! Which local edits fix_infeasible_feature() tries.
enum class LocalEdits {
  Basic,            // splits, vertex moves, disc smoothing
  WithRidgeChamfer  // and, last, the ridge chamfer (once refinement no longer helps)
};

//! Tries the local edits for one feature, cheapest first; keeps the first one
//! after which the exact test finds fewer features (then `features` is that
//! test's result) and returns whether there was one.
//! \param w the mesh and its reference; replaced by the edited ones when an edit is kept.
//! \param features the exact test's result on `w.mesh`, `feature` one of its features.
//! \param cap largest distance of a moved vertex from its reference point, model units.
bool fix_infeasible_feature(RepairWork& w, const InfeasibleFeature& feature, FeasibilityResult& features, double cap,
                            LocalEdits edits);

//! Faces around each vertex, in increasing face id.
std::vector<std::vector<int>> vertex_stars(const Mesh& mesh);

//! Vertices within `rings` edge rings of `v` (v first, then by ring and id).
std::vector<int> ring_vertices(const Mesh& mesh, const std::vector<std::vector<int>>& star, int v, int rings);

}  // namespace subfab::detail
