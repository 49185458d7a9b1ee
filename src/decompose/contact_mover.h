// SPDX-License-Identifier: GPL-3.0-or-later
//! \file contact_mover.h
//! Private: the last resort of carving (thesis Section 4.3.3) for a contact
//! no axis-aligned cut separated (pinch_points.h): moving the box face that
//! holds it off it, by a small step, outward when the box stays exactly
//! valid, else inward when every triangle stays held by some box. Used by
//! carve_blocks(), which carves the changed regions again. Only .cpp files
//! include it.
#pragma once

#include <cstddef>
#include <map>
#include <vector>

#include "decompose/carve_box_region.h"
#include "geometry/solid_index.h"
#include "subfab/decompose/carve_blocks.h"
#include "subfab/geometry/height_box.h"

namespace subfab::detail {

//! Moves box faces off the contacts that no axis-aligned cut separated
//! (carve_blocks()). The region of a box is bounded by its own faces and by
//! faces of earlier boxes (holes); a contact lies in one of them, with the
//! solid on both sides of that plane (the solid is a 2-manifold: the two
//! pieces that touch there are joined across the plane). Moving that face
//! by a small distance across the contact removes it. A face is moved
//! outward (the box grows: every triangle it held is still held) when the
//! moved box stays exactly valid (SolidIndex::box_is_valid) and within the
//! size limits, else inward (the box shrinks) when every triangle meeting the
//! slab it gives up is still held by some box. Later boxes take the moved box
//! as a hole, so the regions stay disjoint; carve_blocks() takes a move back
//! when a region carved again is no longer a height field. Deterministic:
//! moves are decided in box order.
class ContactMover {
 public:
  ContactMover(const detail::SolidIndex& index, std::vector<HeightBox>& boxes, const CarveOptions& options,
               double diagonal)
      : index_(index), boxes_(boxes), options_(options), step_(options.contact_move * diagonal) {}

  //! Has face f been tried fewer than kMaxMovesPerFace times?
  bool can_try(const BoxFace& f) const {
    auto it = num_tried_.find(f);
    return it == num_tried_.end() || it->second < kMaxMovesPerFace;
  }

  //! The positions face f may move to, at the current step of that face
  //! (x10 each time it is tried again): outward first, when the box stays
  //! valid and within the limits; then inward, when every triangle the box
  //! gives up that way is covered by the shrunk box or another box. Empty
  //! when both are refused. carve_blocks() tries them in turn: an outward
  //! move can break a later box's region where the inward one does not.
  std::vector<Box3> candidates(const BoxFace& f);

  //! Moves box f.box to `moved` (one of candidates(f)) and marks the boxes
  //! whose region changes: the box, and every later box overlapping the old
  //! box or the new one.
  void apply(const BoxFace& f, const Box3& moved, std::vector<char>& dirty);

  //! Takes back the last move of face f (the box was `before`); the next
  //! candidates(f) move it further.
  void undo(const BoxFace& f, const HeightBox& before);

  std::size_t num_moves() const { return num_moves_; }

 private:
  //! Box f.box shrunk to `shrunk` across face f: is every triangle that
  //! meets the slab it gives up (closed, exact) still held there by the
  //! shrunk box or another box? Checked on the part of the slab inside the
  //! triangle's bounding box, cell by cell of the other boxes' planes.
  bool keeps_coverage(const BoxFace& f, const Box3& shrunk) const;

  //! Does the union of the closed boxes (box `skip` replaced by `replacement`)
  //! contain the closed box `part` of the triangle (a, b, c)'s bounding box?
  //! Where the triangle lies in a box plane, that box holds it only when the
  //! triangle's normal leaves the box there (the solid on the box's side).
  bool part_is_held(const Box3& part, const Vec3& a, const Vec3& b, const Vec3& c, std::size_t skip,
                    const Box3& replacement) const;

  static constexpr int kMaxMovesPerFace = 3;
  const detail::SolidIndex& index_;
  std::vector<HeightBox>& boxes_;
  const CarveOptions& options_;
  double step_;
  std::map<BoxFace, int> num_tried_;
  std::size_t num_moves_ = 0;
};

}  // namespace subfab::detail
