// SPDX-License-Identifier: GPL-3.0-or-later
//! \file measure_fill_deviation.h
//! How far material added outside a solid moves its surface (issue 17,
//! point 2: the deviation of a decomposition within a tolerance; thesis
//! Section 4.3.5 measures faithfulness the same way, as a Hausdorff
//! distance to the input surface).
//!
//! A decomposition within a tolerance T replaces blocks by their milled
//! shapes (milled_shape.h), which stick out of the input solid S where they
//! fill undercuts. The model then made is S' = S ∪ F_1 ∪ ... ∪ F_n, the F_k
//! the blocks that stick out ("filled" blocks), and the deviation is the
//! symmetric Hausdorff distance between the surfaces ∂S' and ∂S (the cut
//! faces between blocks and the empty interior do not count: they are not
//! on either surface).
//!
//! FillDeviationMeter::measure() computes that distance near one filled
//! block F (the others near it included), exactly where it matters:
//!   1. Q = the input faces whose bounding box meets box(F) widened by the
//!      reach r; R' = the box around box(F) and Q, widened by r (and a hair);
//!   2. V = (F ∪ the other filled blocks, clipped to R'' = R' shrunk by half
//!      the hair) ∪ (S ∩ R'), by exact booleans (CGAL corefinement, exact
//!      kernel, deterministic arena; the two clips' cut faces are never
//!      coplanar, which CGAL corefines slowly); the faces of V on the planes
//!      of R' and R'' are cut faces, the others are ∂S' exactly within R'',
//!      which holds box(F) widened by r;
//!   3. to_input = one-sided Hausdorff distance from those faces to ∂S;
//!      from_input = from Q to those faces (CGAL bounded error).
//! Why local is enough: a point of ∂S' outside box(F) was a point of the
//! surface before F was added, and a point of ∂S farther than r from box(F)
//! keeps a nearest point of ∂S' within r that F does not touch; so with r >=
//! the tolerance, adding F keeps the whole model within the tolerance iff
//! the local distances are within it; and with r >= the tolerance, every
//! nearest point within r of a point of Q lies inside R', where V's surface
//! is ∂S' exactly.
//!
//! measure_fill() (issue 17: the whole-box measure took > 9 min on max
//! planck's big blocks) measures the same distance only where the milled
//! shape F added material to the carved block C, given boxes that cover
//! the fill G = closure(F \ C) (fill_columns() computes them without a
//! boolean). Why that is enough, for C ⊆ S (a carved block) and C ⊆ F:
//!   - a point p of ∂S' in no G_k: if p lay in some F_k \ S it would lie in
//!     F_k \ C_k ⊆ G_k, so p ∈ S, and p ∉ int S' ⊇ int S, so p ∈ ∂S:
//!     distance 0;
//!   - a point x of ∂S in no G_k: x ∉ int C_k (C_k ⊆ S), and x ∈ F_k would
//!     put a neighbourhood of x in F_k inside C_k, so x ∉ int F_k; if a
//!     ball around x lay in S', its points outside S (there are, x ∈ ∂S)
//!     would lie in ∪ F_k \ S ⊆ ∪ G_k, and x in their closure ∪ G_k; so
//!     x ∈ ∂S': distance 0.
//! So only points in the G_k deviate, and each lies in a covering box B;
//! measure_region(B) measures it exactly as above (steps 1-3 with box(F)
//! replaced by B, the block clipped to the region like the others). The
//! result is the maximum over the boxes. Rounding: the carved block's
//! vertices are rounded once from exact points of S, so C ⊆ S holds up to
//! a displacement of a few ulps of the coordinates; measure_fill() adds
//! 16 ulps of the largest coordinate to the error bound for it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "subfab/geometry/axis.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of FillDeviationMeter::measure().
struct FillDeviationOptions {
  double reach = 0.0;  // model units, >= 0: the input surface within this of the block's box is checked
                       // (set it to the tolerance, see the file comment)
  double error = 0.0;  // error bound of the Hausdorff distances, model units (> 0)
  std::size_t max_faces = 0;  // > 0: give up (failure "region too large") when more input faces than this lie in
                              // the region, before any boolean (the exact booleans grow with it); 0 = no cap
};

//! Result of FillDeviationMeter::measure() (model units).
struct FillDeviation {
  double to_input = 0.0;    // one-sided Hausdorff distance from ∂S' near the block to ∂S: how far the added
                            // material sticks out of the input
  double from_input = 0.0;  // one-sided Hausdorff distance from ∂S near the block to ∂S': how deep the input
                            // surface lies under added material
  double error = 0.0;       // error bound of both (the true values are within it)
  std::string failure;      // non-empty when an exact boolean failed: nothing was measured
  //! Upper bound of the symmetric distance (both plus the error bound).
  double bound() const { return std::max(to_input, from_input) + error; }
};

//! Measures the deviation that blocks sticking out of a solid cause, near
//! one of them (see the file comment). Thread-safe: measure() may run
//! concurrently; its result does not depend on the thread that runs it.
class FillDeviationMeter {
 public:
  //! \param solid closed, outward-oriented, self-intersection-free mesh (copied)
  explicit FillDeviationMeter(const Mesh& solid);
  ~FillDeviationMeter();
  FillDeviationMeter(const FillDeviationMeter&) = delete;
  FillDeviationMeter& operator=(const FillDeviationMeter&) = delete;

  //! The deviation of ∂(S ∪ block ∪ others) from ∂S near `block`.
  //! \param block  closed, outward-oriented 2-manifold (a milled shape), same frame as the solid
  //! \param others the other blocks that stick out of the solid (any number: those whose box
  //!               does not meet the region are skipped); none may overlap `block` in volume
  FillDeviation measure(const Mesh& block, const std::vector<const Mesh*>& others,
                        const FillDeviationOptions& options) const;

  //! The same distance, measured only near `core` (a closed box): exact for
  //! the points of ∂S' in `core` and of ∂S in `core` (steps 1-3 of the file
  //! comment with box(block) replaced by `core`). measure() is
  //! measure_region() with core = box(block).
  FillDeviation measure_region(const Mesh& block, const std::vector<const Mesh*>& others, const BoundingBox& core,
                               const FillDeviationOptions& options) const;

  //! The deviation near `block`, measured only in the boxes `fill` that
  //! cover where block sticks out of its carved block (fill_columns()): the
  //! maximum of measure_region() over them, the error bound widened by the
  //! rounding slack of the file comment. No box: nothing deviates (0).
  FillDeviation measure_fill(const Mesh& block, const std::vector<const Mesh*>& others,
                             const std::vector<BoundingBox>& fill, const FillDeviationOptions& options) const;

  const Mesh& solid() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

//! Closed boxes whose union covers the fill G = closure(milled \ carved) of
//! a block milled along an axis (no boolean; exact orientation predicates).
//! With h(v) = v.d and base = min h over the carved block: on a line along
//! d, the milled shape (a height field whose only faces facing away from d
//! lie on the base plane: checked) is [base, top]; where its top face has
//! its vertices among the carved block's and lies in one carved face facing
//! d, the carved block lies just under top; then every point of G on the
//! line lies below a point where the line enters the carved block from
//! below, on a face facing away from d (exact sign) not on the base plane.
//! So G lies in the columns (box extended down to the base plane) of those
//! faces of the carved block and of the milled faces facing d that do not
//! lie in a carved face facing d (exact test). The columns are gathered per
//! tile of an 8 x 8 grid over the footprint (one box per tile).
//! \param carved closed, outward-oriented block (carve_blocks()), inside the solid
//! \param milled its milled shape along `axis` (milled_shape())
//! \return nullopt when the milled mesh is not such a height field (measure
//!         the whole block instead); an empty vector when nothing is added
std::optional<std::vector<BoundingBox>> fill_columns(const Mesh& carved, const Mesh& milled, Axis axis);

//! Closed boxes whose union covers a closed solid `part` (validate's check
//! 10: part = block \ input, the material a block adds; with C = block ∩
//! input the file comment's argument holds, C ⊆ S and C ⊆ F, so only the
//! points in these boxes can deviate). A point of the solid lies under the
//! face where the line through it along an axis leaves the solid, and above
//! the lowest point of its connected component: so the columns (face box
//! extended down to its component's lowest coordinate) of all faces cover
//! it. Columns along the axis whose boxes are smallest in all, gathered per
//! tile of an 8 x 8 grid over the footprint (one box per tile), each widened
//! by 16 ulps of the largest coordinate (the part's vertices were rounded
//! from exact points). Boxes closer than `merge_distance` (model units, >=
//! 0; 0 = none merged) are replaced by their bounding box (check 10 passes
//! twice the reach: such boxes' regions overlap, and one region costs less
//! than two). Empty for an empty mesh.
std::vector<BoundingBox> solid_columns(const Mesh& part, double merge_distance = 0.0);

//! measure_fill() of many blocks at once: one parallel task per box (a big
//! block has many), measure() for a block whose `fills` entry is nullopt
//! (fill_columns() could not bound it). blocks[i] sticks out with the fill
//! boxes fills[i]; `filled` lists every block that sticks out (the others
//! near each region; a block is skipped in its own list). Deterministic
//! whatever the thread count (each task's result is independent of it).
//! \param on_done called after each task (done, total), from any thread
std::vector<FillDeviation> measure_fills(const FillDeviationMeter& meter, const std::vector<const Mesh*>& blocks,
                                         const std::vector<std::optional<std::vector<BoundingBox>>>& fills,
                                         const std::vector<const Mesh*>& filled, const FillDeviationOptions& options,
                                         const std::function<void(std::size_t, std::size_t)>& on_done = {});

}  // namespace subfab
