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
//!   1. Q = the input surface within box(F) widened by the reach r (the
//!      faces whose bounding box meets that box, clipped to it: a long face's
//!      far part would only widen the region, and CAD parts' faces can span
//!      a third of the model); R' = the box around box(F) and Q, widened by
//!      r (and a hair);
//!   2. V = (F ∪ the other filled blocks, clipped to R'' = R' shrunk by half
//!      the hair) ∪ (S ∩ R'), by exact booleans (CGAL corefinement, exact
//!      kernel, deterministic arena; the two clips' cut faces are never
//!      coplanar, which CGAL corefines slowly); the faces of V on the planes
//!      of R' and R'' are cut faces, the others are ∂S' exactly within R'',
//!      which holds box(F) widened by r. Only the surface of V is needed,
//!      not a 2-manifold solid: successive CGAL unions make it when they can;
//!      when one cannot (operands touching along an edge or at a point: the
//!      union is not a 2-manifold, which CGAL refuses), the overlay of
//!      union_surface.h makes it from the same operands (pairwise
//!      corefinement, each face kept iff its interior lies outside every
//!      other operand, exact);
//!   3. to_input = one-sided Hausdorff distance from those faces to ∂S;
//!      from_input = from Q to those faces (CGAL bounded error).
//! Why local is enough: a point of ∂S' outside box(F) was a point of the
//! surface before F was added, and a point of ∂S farther than r from box(F)
//! keeps a nearest point of ∂S' within r that F does not touch; so with r >=
//! the tolerance, adding F keeps the whole model within the tolerance iff
//! the local distances are within it; and with r >= the tolerance, every
//! nearest point within r of a point of Q lies inside R', where V's surface
//! is ∂S' exactly.
//! Any reach gives an upper bound: the patch of step 3 is a part of ∂S' and
//! the input faces a part of ∂S, so each measured distance is >= the true
//! one; and a point whose true distance is <= r has its nearest point in
//! the measured patch, so where the measured maximum (plus the error bound)
//! is <= r it is the true maximum. measure(), measure_fill() and
//! measure_fills() use that (issue 17: egea's fills at T = 8.3e-2 of the
//! diagonal made regions of nearly the whole model, 64 per block): they
//! measure first with reach r1 = first_reach_fraction x the reach, and again
//! with the whole reach only in the boxes whose bound exceeds r1 (the fill
//! boxes of a block closer than twice the reach measured as one region).
//! measure_fills() measures each box before that with measure_local() (Q =
//! the input surface in the box, V made around it and the input faces near
//! it up to the reach), using that ∂S away from every fill box lies on ∂S'
//! (shown below), and that only points of ∂S in the fill boxes can deviate
//! (measure_fill() below; every fill box of every block is measured, with
//! all the filled blocks): an upper bound, kept when <= the reach.
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
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "subfab/geometry/axis.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Per block sticking out of the solid: closed boxes that cover where it
//! does (block \ solid), see FillDeviationOptions::others_cover.
using FillCoverMap = std::map<const Mesh*, std::vector<BoundingBox>>;

//! Options of FillDeviationMeter::measure().
struct FillDeviationOptions {
  double reach = 0.0;  // model units, >= 0: the input surface within this of the block's box is checked
                       // (set it to the tolerance, see the file comment)
  double error = 0.0;  // error bound of the Hausdorff distances, model units (> 0)
  std::size_t max_faces = 0;  // > 0: give up (failure "region too large") when more input faces than this lie in
                              // the region, before any boolean (the exact booleans grow with it); 0 = no cap
  double first_reach_fraction = 0.25;  // (0, 1]: measure() / measure_fill() / measure_fills() measure first with
                                       // this fraction of the reach, and again with the whole reach only the boxes
                                       // whose bound exceeds it (exact either way, see the file comment); 1 = one
                                       // pass. measure_region() uses the reach as given.
  bool local_first = true;  // measure_fills() only (it measures every filled block): true: each box first with
                            // measure_local() (V made around the box alone), that bound kept when it is <=
                            // the reach, the two reaches only for the others; false: the two reaches only.
                            // measure() and measure_fill() measure one block and the input near it for
                            // merges (docs/decompose.md 8b): the two reaches always
  double local_margin = 0.05;  // measure_local() only, fraction of the solid's bounding-box diagonal: V is made
                               // around the box and the input faces meeting it, clipped to the box widened by
                               // max(reach, this): room for the nearest points (a narrower room gives looser
                               // bounds, more of them above the reach); a mesh's faces rarely reach this far
                               // past a box (taken whole then, as before), a CAD part's long faces do (pinion
                               // at 5e-4: each region was a third of the model with the faces whole)
  const FillCoverMap* others_cover = nullptr;  // optional: an other block listed here with boxes covering
                                              // block \ solid is left out of a region none of them meets
                                              // (its part there lies in the solid: nothing changes; validate
                                              // check 10, issue 17: the exported blocks of a turned model,
                                              // rounded back to the input frame, touch one another where
                                              // CGAL cannot unite them, and the overlay is slow); others
                                              // are left out of a region their bounding box does not meet
  bool overlay_only = false;  // true: always make the local surface with union_surface()'s overlay (tests and
                              // measurements); false: successive CGAL unions, the overlay when one fails
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

  //! The same distance, measured only near `core` (a closed box), with the
  //! reach as given: an upper bound for the points of ∂S' in `core` and of
  //! ∂S in `core`, exact where it is <= the reach (steps 1-3 of the file
  //! comment with box(block) replaced by `core`). measure() is
  //! measure_region() with core = box(block), first with a smaller reach.
  FillDeviation measure_region(const Mesh& block, const std::vector<const Mesh*>& others, const BoundingBox& core,
                               const FillDeviationOptions& options) const;

  //! The deviation near `block`, measured only in the boxes `fill` that
  //! cover where block sticks out of its carved block (fill_columns()): the
  //! maximum of measure_region() over them, the error bound widened by the
  //! rounding slack of the file comment. No box: nothing deviates (0).
  FillDeviation measure_fill(const Mesh& block, const std::vector<const Mesh*>& others,
                             const std::vector<BoundingBox>& fill, const FillDeviationOptions& options) const;

  //! An upper bound of the same distance near `core` with V made around
  //! `core` and the input faces meeting it, clipped to `core` widened by
  //! FillDeviationOptions::local_margin (no reach around that), cheaper than measure_region() when the reach
  //! is large (issue 17: egea at 8.3e-2 of the diagonal). `outside` (from
  //! faces_outside()) marks the input faces that meet no box covering any
  //! filled block's fill: those lie on ∂S' (see the file comment), the
  //! buried input faces in `core` are measured to them and to V's faces in
  //! V's inner box; the patch to the input faces within the reach. Exact
  //! when each nearest point lies in V's inner box or on such a face, an
  //! upper bound always (both targets are parts of the true surfaces).
  FillDeviation measure_local(const Mesh& block, const std::vector<const Mesh*>& others, const BoundingBox& core,
                              const std::vector<char>& outside, const FillDeviationOptions& options) const;
  //! Per input face: 1 when its bounding box meets no box of `cover`.
  std::vector<char> faces_outside(const std::vector<BoundingBox>& cover) const;

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

//! fill_columns() before the tiling: one column per face that can bound
//! the fill from above (a finer cover, of many more boxes).
std::optional<std::vector<BoundingBox>> fill_face_columns(const Mesh& carved, const Mesh& milled, Axis axis);

//! fill_columns()'s tiling of such columns: one box per tile of an 8 x 8
//! grid over the footprint of `milled` along `axis` (each column in the tile
//! of its lowest corner; none when there are none).
std::vector<BoundingBox> tile_columns(const std::vector<BoundingBox>& columns, const Mesh& milled, Axis axis);

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
//! from exact points). Only the part's boundary faces are read, so `part`
//! may be the triangle soup bounding a solid that is not a 2-manifold
//! (pieces touching along an edge: OutsidePart::boundary): the face where
//! the line leaves the solid for the last time is on the shell around the
//! point, which shares vertices, hence a component, with nothing lower than
//! it. Boxes closer than `merge_distance` (model units, >=
//! 0; 0 = none merged) are replaced by their bounding box (measure_fills()
//! merges the boxes closer than twice the reach of each of its passes: such
//! boxes' regions overlap, and one region costs less than two). Empty for
//! an empty mesh.
std::vector<BoundingBox> solid_columns(const Mesh& part, double merge_distance = 0.0);

//! 16 ulps of the largest coordinate of the vertices `mesh`'s faces use: how
//! far a mesh whose vertices were each rounded once from exact points lies
//! from the exact one (the rounding slack of measure_fill(), see above).
double rounding_slack(const Mesh& mesh);

//! measure_fill() of many blocks at once: one parallel task per box (a big
//! block has many; in each pass, boxes of a block closer than twice the pass's
//! reach merged); a block whose `fills` entry is nullopt (fill_columns()
//! could not bound it) is measured in solid_columns() of the whole block. blocks[i] sticks out with the fill
//! boxes fills[i]; `filled` lists every block that sticks out (the others
//! near each region; a block is skipped in its own list). Deterministic
//! whatever the thread count (each task's result is independent of it).
//! \param on_done called after each task (done, total), from any thread
std::vector<FillDeviation> measure_fills(const FillDeviationMeter& meter, const std::vector<const Mesh*>& blocks,
                                         const std::vector<std::optional<std::vector<BoundingBox>>>& fills,
                                         const std::vector<const Mesh*>& filled, const FillDeviationOptions& options,
                                         const std::function<void(std::size_t, std::size_t)>& on_done = {});

}  // namespace subfab
