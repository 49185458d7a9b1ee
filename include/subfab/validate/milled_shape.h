// SPDX-License-Identifier: GPL-3.0-or-later
//! \file milled_shape.h
//! What a 3-axis machine really makes of a block (issue 17, point 1; thesis
//! Section 4.3.5 trades faithfulness for fewer blocks, and this is how the
//! trade is measured). A tool coming from the block's milling direction d
//! removes everything above the block's top surface and nothing under an
//! overhang, so what it mills is the block's MILLED SHAPE: for every line
//! parallel to d through the block, the segment from the base plane (the
//! minimum of v.d over the block) up to the block's highest point on that
//! line. For an exact height field it is the block itself.
//!
//! milled_shape() builds it; measure_milled_shapes() measures, for every
//! block of a decomposition, how far the milled shape strays from the block
//! and from the input, and whether milled shapes collide.
//!
//! Outline of milled_shape():
//!   1. exact height field (check_height_field() passes)? return the block;
//!   2. rotate the block so that d is +z (a signed permutation when d is an
//!      axis: no rounding);
//!   3. upper envelope of the faces that face +z (CGAL Envelope_3, exact
//!      kernel): a planar arrangement whose faces carry the triangle on top;
//!   4. lift every face onto its triangle, add a vertical wall wherever the
//!      height jumps across an arrangement edge (down to the base at the
//!      outer boundary), and the base under every face; triangulate them
//!      (constrained Delaunay, exact) with shared exact vertices;
//!   5. round once to doubles and rotate back.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of milled_shape().
struct MilledShapeOptions {
  double normal_tolerance = 1e-3;  // exact-height-field test (check_height_field): faces with unit
                                   // n.d >= -this count as facing d (unitless; 1e-3 = check 2's margin
                                   // for the rounding of exact blocks to doubles)
  double plane_tolerance = 0.0;    // max |v.d - base| of a base vertex in that test (model units;
                                   // 0 = 1e-9 x block size, as check_height_field)
  std::optional<Eigen::Matrix3d> frame;  // rotation taking d to +z (e.g. the block's machine frame);
                                         // unset: a signed permutation when d is an axis, else one
                                         // built from d
};

//! Which part of the milled shape a face belongs to.
enum class MilledFaceKind : unsigned char {
  Top,   // on a face of the block that faces d (the block's own surface)
  Wall,  // vertical (parallel to d): where the top surface jumps, or down to the base
  Base,  // on the base plane, facing -d
};

//! Result of milled_shape().
struct MilledShape {
  Mesh mesh;                              // closed, outward oriented, input coordinates
  bool is_block = false;                  // the block is an exact height field: mesh is the block
  std::vector<MilledFaceKind> face_kinds; // one per face of mesh (empty when is_block)
  double base = 0.0;                      // base plane: min over the block's vertices of v.d (model units)
  std::size_t num_envelope_faces = 0;     // faces of the envelope arrangement with a triangle on top
};

//! The milled shape of `block` along the unit milling direction `direction`
//! (the tool comes from +direction). Topology is decided exactly (CGAL
//! Envelope_3 and constrained Delaunay triangulations on the exact kernel);
//! coordinates are rounded once at the end, then rotated back (exactly when
//! the frame is a signed permutation). The mesh is closed and consistently
//! oriented; it can have non-manifold edges or vertices where the milled
//! solid itself touches along a vertical line or at a point.
//! \param block closed, outward-oriented triangle mesh (input coordinates)
//! \throw InvalidArgumentError if direction is not a unit vector or the frame
//!        is not a rotation taking it to +z.
MilledShape milled_shape(const Mesh& block, const Vec3& direction, const MilledShapeOptions& options = {});

//! A rotation taking the unit vector `direction` to +z: a signed permutation
//! when it is an axis (exact), else rows (u, v, d) with u, v orthonormal.
Eigen::Matrix3d milling_frame(const Vec3& direction);

// ------------------------------------------------------------- measures
//! One block to measure.
struct MilledBlockInput {
  const Mesh* mesh = nullptr;             // the block (input coordinates)
  Vec3 direction = Vec3::UnitZ();         // unit milling direction (input coordinates)
  std::optional<Eigen::Matrix3d> frame;   // rotation taking direction to +z, if known
};

//! Options of measure_milled_shapes().
struct MilledMeasureOptions {
  double normal_tolerance = 1e-3;     // see MilledShapeOptions (unitless cosine)
  double hausdorff_error = 1e-5;      // error bound of the distances (fraction of the input's bbox diagonal)
  double collision_tolerance = 1e-6;  // a collision: overlap volume > this x the smaller milled shape (unitless)
  Progress* progress = nullptr;       // one update per block and per pair (nullptr: silent)
};

//! Measures of one block's milled shape (model units; fractions of the
//! input's bounding-box diagonal are derived by the caller).
struct MilledShapeMeasures {
  bool exact = true;               // exact height field: the milled shape is the block, nothing below is computed
  std::size_t num_faces = 0;       // faces of the milled shape
  double block_volume = 0.0;       // model units^3
  double volume = 0.0;             // the milled shape's volume, model units^3
  double filled_volume = 0.0;      // volume - block_volume: material left under overhangs, model units^3
  double deviation = 0.0;          // one-sided Hausdorff distance from the milled surface to the union of the
                                   // input surface and the block surface, model units: the block's own
                                   // surface counts 0, every other point the distance to the input surface
                                   // (or to the block, when that is nearer: material inside the model)
  double deviation_to_block = 0.0; // one-sided Hausdorff distance from the milled surface to the block
                                   // surface (how deep the undercuts are), model units
  double outside_volume = 0.0;     // vol(milled \ input), model units^3 (exact boolean)
  double outside_distance = 0.0;   // farthest point of milled \ input from the input surface, model units
  std::string error;               // non-empty when a measure could not be computed (then it is 0)
};

//! A pair of milled shapes that overlap.
struct MilledCollision {
  std::size_t a = 0, b = 0;  // block indices, a < b
  double volume = 0.0;       // exact overlap volume, model units^3
};

//! Result of measure_milled_shapes().
struct MilledShapesReport {
  std::vector<MilledShapeMeasures> blocks;  // one per block, in order
  std::vector<MilledCollision> collisions;  // overlaps above the tolerance, by (a, b)
  std::size_t num_pairs_checked = 0;        // pairs with at least one non-exact block and overlapping boxes
  double hausdorff_error = 0.0;             // error bound of every distance, model units
  std::size_t num_exact() const;
  double max_deviation() const;             // over blocks, model units
  double total_filled_volume() const;       // model units^3
};

//! Milled shape of every block (parallel over blocks, deterministic) and
//! its measures. Distances: CGAL bounded-error Hausdorff (error <=
//! hausdorff_error x diagonal); volumes: exact booleans (the validator's,
//! with its Nef fallback). Collisions are computed for pairs where at least
//! one block is not exact (exact pairs are check 3 of validate_decomposition()).
//! Failures of a block's booleans are reported in its `error`, not thrown.
MilledShapesReport measure_milled_shapes(const Mesh& input, const std::vector<MilledBlockInput>& blocks,
                                         const MilledMeasureOptions& options = {});

}  // namespace subfab
