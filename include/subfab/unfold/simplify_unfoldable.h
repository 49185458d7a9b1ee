// SPDX-License-Identifier: GPL-3.0-or-later
//! \file simplify_unfoldable.h
//! The unfoldable simplification of thesis Chapter 3, stages 1-6 chained:
//!   1. lattice over the bounding box, exact inside/outside signs (3.3.1);
//!   2. marching cubes with every normal in the 26-direction set (3.2);
//!   3. charts: coplanar triangles merged into planar facets;
//!   4. masks: lattice sign flips that remove bad configurations (3.3.1, App. A);
//!   5. facet deletion: small facets (and the ids the user gives) removed, holes
//!      closed by extending the neighbouring planes, exactly (3.3.2);
//!   6. unfolding into nets without overlaps (3.3.3);
//! then verifies the result (exact polygonal-mesh check, no net overlaps,
//! refolding reproduces the model) and measures the Hausdorff distance to the
//! input. Export (stage 7) is export_unfolding().
#pragma once

#include <vector>

#include "subfab/core/progress.h"
#include "subfab/mesh/mesh.h"
#include "subfab/unfold/delete_facets.h"
#include "subfab/unfold/export_unfolding.h"
#include "subfab/unfold/poly_mesh.h"
#include "subfab/unfold/unfold_nets.h"

namespace subfab {

//! Options of simplify_unfoldable().
struct SimplifyUnfoldableOptions {
  double granularity = 2.0;  // grid spacing = average edge length x granularity (> 0)
  //! Facets smaller than this are deleted automatically (model units^2);
  //! < 0: 4 x spacing^2 (four grid cells); 0: no automatic deletion.
  double min_facet_area = -1;
  //! Facet ids to delete as well, numbered as in the result of the same call
  //! without them (after the automatic deletion); adjacent ids go together.
  std::vector<int> delete_facet_ids;
  bool masks = true;  // run stage 4 (false: the charts go to deletion unchanged)
  Progress* progress = nullptr;  // stages, counts, warnings; may be null
};

//! Result of simplify_unfoldable().
struct SimplifyUnfoldableResult {
  PolyMesh mesh;          // the simplified closed polygonal mesh (model units)
  Unfolding unfolding;    // its nets
  UnfoldSummary summary;  // facet counts per stage, nets, Hausdorff distance
  double spacing = 0;     // grid spacing (model units)
  Vec3 origin = Vec3::Zero();  // lattice origin (model units)
  double min_facet_area = 0;   // area threshold used (model units^2)
  double refold_error = 0;     // largest refolded-corner error (model units)
  double hausdorff_after_masks = 0;  // Hausdorff distance input <-> mask-stage surface (model units)
  std::vector<FacetDeletionFailure> failures;  // deletions refused, with reasons
};

//! Runs stages 1-6 on a closed solid and verifies the result.
//! \param mesh closed, manifold, outward-oriented triangle mesh (pass it
//!        through require_closed_solid() first).
//! \throw InvalidArgumentError on bad options (granularity <= 0, unknown ids);
//!        AlgorithmError when the result fails its verification.
SimplifyUnfoldableResult simplify_unfoldable(const Mesh& mesh, const SimplifyUnfoldableOptions& options = {});

}  // namespace subfab
