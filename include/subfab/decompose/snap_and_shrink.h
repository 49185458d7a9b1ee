// SPDX-License-Identifier: GPL-3.0-or-later
//! \file snap_and_shrink.h
//! Block snapping and shrinking (thesis Section 4.3.4, "Block Snapping and
//! Shrinking"): before overlap resolution, align nearly coincident box faces
//! and trim overlaps, so that the conflict graph has fewer edges and cycles
//! and the carved blocks have fewer thin slivers.
//!
//! Outline of snap_and_shrink():
//!   1. snap: candidate pairs of parallel faces of two boxes (opposite-facing:
//!      A's +e face and B's -e face; or same-facing) whose distance is below
//!      snap_distance and whose rectangles overlap across the axis; sorted by
//!      distance (then box ids), each aligns one face onto the other: the move
//!      that enlarges a box is tried first, then the one that shrinks. A move
//!      is applied only if the moved box stays exactly valid (SolidIndex) and
//!      every face it covered is still covered by some box; an aligned face is
//!      not moved again;
//!   2. shrink: for every pair of overlapping boxes (in index order), the
//!      smallest trim of one box that removes the overlap (one face of one box
//!      moved onto the other box's opposite face) such that every face stays
//!      covered; repeated until nothing changes. Trimmed boxes are sub-boxes,
//!      hence valid.
//! Coverage means the cover stage's notion (SolidIndex::faces_covered: each
//! triangle entirely inside some box); faces no input box covered are ignored.
//! Deterministic.
#pragma once

#include <array>
#include <cstdint>

#include <limits>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/geometry/height_box.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of snap_and_shrink().
struct SnapShrinkOptions {
  double snap_distance = -1;     // model units; < 0: the mesh's average edge length (one grid
                                 // cell at grid factor 1); 0: no snapping
  bool shrink = true;            // trim overlaps after snapping
  int max_shrink_passes = 4;     // passes over all overlapping pairs (>= 0)
  double max_height = std::numeric_limits<double>::infinity();  // block height limit along the
                                 // box's axis, model units: a snap never enlarges a box past it
  Vec3 machine_size = Vec3::Constant(std::numeric_limits<double>::infinity());  // work volume
                                 // X, Y, Z in model units (Z along the axis; see box_fits_limits)
  double max_overhang_deg = 0.0;  // faces may lean this far past vertical and count as facing the axis (degrees,
                                  // [0, 45], see overhang_sine(); 0 = exact height fields)
  const std::vector<std::uint8_t>* allowed_overhangs = nullptr;  // per face of the mesh passed: bit k set = the
                                  // face counts as facing both +-e_k (decompose --tolerance: its undercut is within
                                  // the tolerance, tolerance_allowances()); nullptr = none
  const std::vector<std::array<double, 3>>* overhang_floors = nullptr;  // with allowed_overhangs, per face and
                                  // dimension k: the allowance of bit k holds only in boxes whose base (min of x.d
                                  // over the box, d the direction along e_k the face faces away from) is >= this
                                  // (-inf: every box; see solid_index.h and tolerance_allowances.h); nullptr = every box
  Progress* progress = nullptr;  // stage reporting (nullptr = silent)
};

//! Result of snap_and_shrink().
struct SnapShrinkResult {
  std::vector<HeightBox> boxes;  // same count and order as the input
  int num_snapped = 0;           // face alignments applied
  int num_shrunk = 0;            // overlap trims applied
};

//! Snaps and shrinks valid height boxes (thesis Section 4.3.4).
//! \param mesh  closed, outward-oriented triangle mesh (canonical frame)
//! \param boxes valid height boxes (e.g. the minimal cover)
//! \return the adjusted boxes, all valid, covering every face the input covered
//! \throw InvalidArgumentError if a box is invalid or has non-finite corners,
//!        or max_shrink_passes < 0.
SnapShrinkResult snap_and_shrink(const Mesh& mesh, std::vector<HeightBox> boxes, const SnapShrinkOptions& options);

}  // namespace subfab
