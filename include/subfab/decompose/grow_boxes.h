// SPDX-License-Identifier: GPL-3.0-or-later
//! \file grow_boxes.h
//! Maximal height-field boxes covering the surface (thesis Section 4.3.2,
//! "Maximal Height-Field Block Set", objective of Appendix B).
//!
//! Outline of grow_boxes():
//!   1. fields = compute_fields(mesh) (or the caller's): Good grid points
//!      near triangles facing each direction;
//!   2. repeat in rounds until every face is covered:
//!      a. seeds: up to `batch_size` faces not yet covered, spread over the
//!         surface (farthest-point order from all previous seeds);
//!      b. grow every seed in parallel, along every axis its triangle faces
//!         (options.all_axes) and with every GrowStrategy (a dense set of
//!         maximal boxes for the cover to choose from): start from the seed
//!         triangle's bounding box; move box faces outward one grid plane at
//!         a time (Greedy: always the face whose new plane holds the most
//!         Good points, the thesis's field integral minimised greedily, until
//!         no move gains anything; Balanced / AcrossFirst: every side in
//!         turn until blocked), each move limited EXACTLY by first contact
//!         with a triangle facing away from the axis (the grid's Forbidden
//!         counts accept a move at once when no Forbidden point is near,
//!         else SolidIndex::push_face) and by the size limits; then push
//!         every side to first contact (a maximal box); shrink each side
//!         back to the covered triangles when that loses no coverage;
//!      c. coverage of the new boxes (exact rule of SolidIndex);
//!   3. faces no axis can cover (a triangle larger than the local feature
//!      size: a facing-away triangle crosses its own bounding box) are split
//!      one-to-four (refine_mesh, Section 4.3.5) and seeding goes on, up to
//!      `max_refinement_levels` times. A face with a crease no axis sees
//!      from both sides (an edge in no axis-aligned plane between faces
//!      with no common facing axis: a fold, thin fin or groove) can never be
//!      covered: AlgorithmError at once, naming the edge.
//!   4. per box, the number of blocks it would give alone (connected pieces
//!      of the surface inside it; carve makes one block per piece): the
//!      cover's cost, so that the cover minimises blocks, not boxes (adding
//!      one box per piece as extra candidates, as the authors' code does,
//!      gave more blocks after resolve on airplane and kitten).
//! Every box returned is exactly valid and every face of the returned mesh
//! is covered by at least one box. Deterministic for any thread count.
#pragma once

#include <cstdint>

#include <array>
#include <limits>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/decompose/compute_field.h"
#include "subfab/geometry/height_box.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Which maximal box a seed grows into (several per seed give the cover a
//! choice; the thesis computes a dense set of maximal boxes, Section 4.3.2).
enum class GrowStrategy {
  Greedy,      // side whose next grid plane holds the most Good points first (App. B objective)
  Balanced,    // every side one grid plane in turn until all are blocked
  AcrossFirst, // the four sides across the axis in turn first (wide, shallow), then the two along it
};

//! Options of grow_boxes().
struct GrowOptions {
  double grid_factor = 1.0;  // grid spacing = average edge length x grid_factor (> 0); unused when `fields` is given
  double max_height = std::numeric_limits<double>::infinity();  // max box extent along its axis, model units (inf = none)
  Vec3 machine_size = Vec3::Constant(std::numeric_limits<double>::infinity());  // work volume X, Y, Z, model units:
      // box extent along its axis <= Z, the two other extents fit X x Y in either order (inf = none)
  std::vector<GrowStrategy> strategies{GrowStrategy::Greedy, GrowStrategy::Balanced,
                                      GrowStrategy::AcrossFirst};  // boxes grown per seed and axis (non-empty)
  bool all_axes = true;             // grow along every axis the seed faces (false: only the first that works)
  int batch_size = 64;              // seeds grown in parallel per round (results do not depend on threads)
  int max_refinement_levels = 8;    // rounds of local 1-to-4 refinement before giving up
  const std::array<HeightField, 6>* fields = nullptr;  // precomputed fields of `mesh` (nullptr: computed here;
                                    // given fields must have been computed with the same max_overhang_deg)
  double max_overhang_deg = 0.0;  // faces may lean this far past vertical and count as facing the axis (degrees,
                                  // [0, 45], see overhang_sine(); 0 = exact height fields)
  const std::vector<std::uint8_t>* allowed_overhangs = nullptr;  // per face of the mesh passed: bit k set = the
                                  // face counts as facing both +-e_k (decompose --tolerance: its undercut is within
                                  // the tolerance, tolerance_allowances()); nullptr = none
  const std::vector<std::array<double, 3>>* overhang_floors = nullptr;  // with allowed_overhangs, per face and
                                  // dimension k: the allowance of bit k holds only in boxes whose base (min of x.d
                                  // over the box, d the direction along e_k the face faces away from) is >= this
                                  // (-inf: every box; see solid_index.h and tolerance_allowances.h); nullptr = every box
  const std::vector<HeightBox>* carried = nullptr;  // boxes kept from an earlier decomposition of the same
                                  // solid (decompose()'s rounds within a tolerance: the boxes of the blocks that
                                  // passed the measure): each one still exactly valid under these allowances and
                                  // within the limits is a candidate from the start, its faces covered, so seeds
                                  // grow only where none holds (nullptr = none)

  Progress* progress = nullptr;     // updates (faces covered / total) and warnings; nullptr = silent
};

//! Result of grow_boxes().
struct GrowResult {
  Mesh mesh;                               // the mesh the boxes refer to: the input, or its local refinement
  std::vector<int> parent_face;            // per face of `mesh`: the input face it lies in
  std::vector<HeightBox> boxes;            // exactly valid boxes (canonical frame, model units)
  std::vector<std::vector<int>> covered;   // per box: sorted ids of the faces of `mesh` it covers
  std::vector<int> num_pieces;             // per box: blocks it would give alone (connected surface pieces
                                           // inside it, >= 1; a predictor for the cover's costs)
  int num_refined_faces = 0;               // input faces that were split (1-to-4 or, for conformity, 1-to-2)
  int num_rounds = 0;                      // seeding rounds
  int num_seeds = 0;                       // seeds grown (including those that failed)
};

//! Grows maximal valid height-field boxes until they cover every triangle
//! (thesis Section 4.3.2 with Appendix B's objective; Section 4.3.5 for the
//! refinement). Boxes are valid in the exact sense of the decomposition: no
//! triangle facing away from the box's axis meets its open interior. A face
//! is covered when it lies in the closed box with the solid on the box's
//! side (see src/geometry/solid_index.h).
//! \param mesh closed, manifold, oriented, self-intersection-free triangle
//!        mesh in the canonical frame (after orient), model units.
//! \throw InvalidArgumentError on non-positive or NaN options.
//! \throw AlgorithmError if a face cannot be covered even after
//!        `max_refinement_levels` refinements (message names the face).
GrowResult grow_boxes(const Mesh& mesh, const GrowOptions& options);

}  // namespace subfab
