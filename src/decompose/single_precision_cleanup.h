// SPDX-License-Identifier: GPL-3.0-or-later
//! \file single_precision_cleanup.h
//! Private (export): makes a block's machine mesh stay a solid once written
//! in single precision (binary STL, float32), issue 17. Rounding to float32
//! can collapse a sheet thinner than float32's spacing (its vertices weld,
//! faces lose their area) or push a vertex through a face nearby (the mesh
//! then intersects itself). Decompositions without slivers rarely need it.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include <Eigen/Core>

#include "subfab/decompose/finalize_blocks.h"
#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! What clean_single_precision() did.
struct SinglePrecisionCleanup {
  std::size_t num_collapsed = 0;  // vertices merged into another that rounds to the same float point,
                                  // or collapsed along an edge shorter than 4 float spacings
  std::size_t num_faces_removed = 0;  // faces that lost their area, or coincident pairs of opposite faces
  std::size_t num_nudged = 0;     // vertices rounded the other way (toward the neighbouring float)
  bool ok = true;                 // the float32 mesh is a closed solid without self-intersections
                                  // (and the block passes `block_valid`)
  bool block_invalid = false;     // a float32 repair was found but the block it made failed `block_valid`
};

//! Checks `machine` (machine coordinates) in float32 (check_single_precision())
//! and, when it fails, repairs it: vertices that round to the same float
//! point are merged (in `machine` and in `block`, its input-frame twin with
//! the same vertex ids, which takes the position of the merged vertex's
//! representative), faces without area and coincident opposite face pairs
//! are removed from both; vertices of faces that still intersect in float32
//! are rounded the other way, coordinate by coordinate (up to 8 candidates
//! per vertex, kept when they reduce the number of intersecting pairs). When
//! that still fails, it starts again from the given meshes after collapsing
//! the edges shorter than 4 float spacings (at the largest coordinate),
//! shortest first, where the link condition keeps a 2-manifold: a cluster of
//! vertices within a few floats of each other (pinion.off: 9 vertices within
//! 2e-8) welds as a whole, which merging equal floats alone cannot do without
//! pinching the surface; that result is kept when it is a solid. The
//! machine mesh's coordinates are left as floats. `ok` says whether the
//! float32 mesh is a solid at the end (it is checked again).
//! A repair is kept only when `block_valid` (when given) accepts the block it
//! makes (export passes block_defect(): closed, no self-intersection, height
//! field), since a merge moves the block's vertex too.
SinglePrecisionCleanup clean_single_precision(Mesh& machine, Mesh& block, const Eigen::Matrix3d* to_machine = nullptr,
                                              const std::function<bool(const Mesh&)>& block_valid = {});

//! Export's float32 step for one finished block (`block`, input frame, as
//! finalize_blocks() makes it; `machine`, its twin in machine coordinates,
//! `to_machine` the rotation between them): clean_single_precision() with
//! a repair kept only when the block then passes block_defect() along
//! `direction` (its unit milling direction, input frame) with `diagonal`
//! (the decomposed input's, as finalize_blocks() checks) and `options`.
//! export_decomposition() writes what this makes, and decompose() vets the
//! blocks its merges make with it, so that a merge kept there cannot have
//! its STL refused at export.
SinglePrecisionCleanup clean_block_for_stl(Mesh& machine, Mesh& block, const Eigen::Matrix3d& to_machine,
                                           const Vec3& direction, double diagonal, const FinalizeOptions& options);

}  // namespace subfab::detail
