// SPDX-License-Identifier: GPL-3.0-or-later
//! \file solid_index.h
//! Private exact geometry index of the decomposition stages (grow, cover,
//! resolve): which triangles face away from a milling direction, whether a
//! triangle meets the open interior of a box, whether a box is a valid
//! height-field box (thesis Section 4.3.2), which triangles a box covers,
//! and exact inside/outside of points.
//!
//! Every decision is exact: signs of polynomials of degree <= 3 in the
//! double inputs are evaluated with a floating-point filter (Shewchuk's
//! error bounds) and exact rationals when the filter cannot decide. No
//! tolerance, no random rays: results depend only on the input doubles.
//!
//! Conventions (the tests check them):
//! - n = (b - a) x (c - a) of face (a, b, c). Face f faces direction d when
//!   the exact sign of n.d is >= 0, and faces away when it is < 0. Under an
//!   overhang allowance s > 0 (--max-overhang, see overhang_sine()) it faces
//!   d when the unit normal has n.d >= -s (facing_signs(), double unit
//!   normal against s); everything else stays exact, is_inside and the
//!   box-plane test of coverage included.
//! - Base floors (decompose --tolerance, issue 17): an allowance may hold
//!   only in boxes whose base lies high enough under the face. The BASE of a
//!   box for axis d is min over the box of x.d (box.min[k] for +e_k,
//!   -box.max[k] for -e_k); face f's FLOOR for d is -inf when f faces d
//!   (exactly, within s, or allowed in every box), a finite value F when f
//!   faces away from d but is allowed in boxes whose base is >= F (the fill
//!   under it is then short, see tolerance_allowances.h), +inf otherwise.
//!   facing_sign() is < 0 iff the floor is > -inf. Comparisons of the base
//!   with a floor are plain double comparisons (deterministic).
//! - A box is VALID for axis d iff no face facing away from d whose floor
//!   lies above the box's base meets the OPEN interior of the box (touching
//!   its boundary is allowed). A box with a zero extent has an empty
//!   interior and is always valid. A box inside a valid box is valid (its
//!   base is not lower).
//! - A face is COVERED by a box for axis d iff its three vertices lie in the
//!   closed box and, for every boundary plane of the box the face lies in,
//!   its normal points out of the box through that plane (so the solid is on
//!   the box's side); a face lying in no boundary plane must face d, or have
//!   its floor at or below the box's base. Hence
//!   the base face of a cube (n = -d) is covered by the cube's box for d, a
//!   face lying in a side plane with the solid outside the box is not, and a
//!   box with a zero extent covers nothing. For a valid box, covered faces
//!   lie on the boundary of the block (solid intersected with the box).
//! - is_inside(p) is the classification of p + (e, e^2, e^3) for an
//!   infinitesimal e > 0 (simulation of simplicity), like compute_fields:
//!   a point on the surface gets a definite, consistent answer.
//!
//! All query methods are const and thread-safe. Boxes passed to queries must
//! have finite coordinates.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "subfab/geometry/axis.h"
#include "subfab/geometry/height_box.h"
#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! The base of `box` for `axis`: min over the box of x.d (see above).
double box_base(const Box3& box, Axis axis);

class SolidIndex {
 public:
  //! Builds the index (copies the mesh). O(F log F).
  //! \param mesh closed, oriented, self-intersection-free triangle mesh
  //!        (canonical frame); is_inside is meaningless otherwise.
  //! \param overhang_sine allowance s >= 0 of the facing test (0: exact)
  //! \param allowed optional per-face allowances of the facing test (see
  //!        facing_signs(); decompose --tolerance), copied
  //! \param floors optional (needs `allowed`), per face and dimension k: the
  //!        base floor of the allowance of bit k (for the direction along
  //!        e_k the face faces away from; -inf: every box, +inf: none; see
  //!        the file comment); nullptr: every allowance holds in every box
  explicit SolidIndex(const Mesh& mesh, double overhang_sine = 0.0,
                      const std::vector<std::uint8_t>* allowed = nullptr,
                      const std::vector<std::array<double, 3>>* floors = nullptr);
  ~SolidIndex();
  SolidIndex(const SolidIndex&) = delete;
  SolidIndex& operator=(const SolidIndex&) = delete;
  SolidIndex(SolidIndex&&) noexcept;
  SolidIndex& operator=(SolidIndex&&) noexcept;

  const Mesh& mesh() const;
  int num_faces() const;

  //! Sign (-1, 0, +1) of n.d for face `face` and direction `axis` (exact;
  //! with an overhang allowance s, -1 iff the unit n.d < -s, 0 iff within s;
  //! 0 where an allowance holds in every box; -1 where it depends on the
  //! box's base).
  int facing_sign(int face, Axis axis) const;
  //! The face's base floor for `axis` (see the file comment).
  double base_floor(int face, Axis axis) const;
  //! Has some face a finite base floor for `axis`?
  bool has_conditional_faces(Axis axis) const;
  //! Exact: does no face with a finite floor above the box's base meet the
  //! open box (box_is_valid() restricted to those faces)?
  bool conditional_faces_allow(const Box3& box, Axis axis) const;
  //! Faces with facing_sign < 0, sorted by id.
  const std::vector<int>& faces_facing_away(Axis axis) const;
  //! Bounding box of a face (exact: min/max of its vertex coordinates).
  const Box3& face_box(int face) const;

  //! Exact: does face `face` meet the open interior of `box`?
  bool face_meets_open_box(int face, const Box3& box) const;

  //! Exact validity (see the file comment).
  bool box_is_valid(const Box3& box, Axis axis) const;
  bool box_is_valid(const HeightBox& box) const { return box_is_valid(box.box, box.axis); }

  //! Faces facing away from `axis` that meet the open box (the reasons a box
  //! is invalid), sorted by id, at most `max_count` of them (the smallest ids).
  std::vector<int> blocking_faces(const Box3& box, Axis axis,
                                  std::size_t max_count = std::numeric_limits<std::size_t>::max()) const;

  //! All faces (any orientation) that meet the open box, sorted by id.
  std::vector<int> faces_meeting_open_box(const Box3& box) const;

  //! Exact: does any face (any orientation) meet the open box? Early-exit
  //! query; with is_inside(box.min) it decides whether the solid's interior
  //! meets the open box (for resolve/carve).
  bool any_face_meets_open_box(const Box3& box) const;

  //! Faces whose bounding box meets the CLOSED box (candidates for exact
  //! closed-box tests), sorted by id.
  std::vector<int> faces_near_closed_box(const Box3& box) const;

  //! Faces covered by the box for `axis` (see the file comment), sorted by id.
  std::vector<int> faces_covered(const Box3& box, Axis axis) const;
  std::vector<int> faces_covered(const HeightBox& box) const { return faces_covered(box.box, box.axis); }
  //! Is face `face` covered by the box for `axis`?
  bool face_covered(int face, const Box3& box, Axis axis) const;

  //! Moves one face of a VALID box outward as far as possible, up to `limit`:
  //! returns the largest double t between the face's current position and
  //! `limit` (inclusive) such that the box with that face at t is still valid
  //! for `axis`. `dim` in 0..2; `side` +1 moves box.max[dim] up
  //! (limit >= box.max[dim]), -1 moves box.min[dim] down (limit <= box.min[dim]).
  //! Exact (first contact with the facing-away triangles; with base floors,
  //! moving the base also stops where it would pass the floor of a face
  //! meeting the box).
  double push_face(const Box3& box, Axis axis, int dim, int side, double limit) const;

  //! Exact, deterministic inside test (parity of exact crossings of a ray
  //! along +z, with the symbolic perturbation described above).
  bool is_inside(const Vec3& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace subfab::detail
