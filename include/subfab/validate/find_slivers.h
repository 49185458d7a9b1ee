// SPDX-License-Identifier: GPL-3.0-or-later
//! \file find_slivers.h
//! Slivers: blocks much thinner than the model they are cut from (issue 17,
//! "no slivers"; thesis Section 4.3.4, whose snapping and merging exist to
//! prevent them). A sheet thinner than a tool cannot be milled or glued, and
//! its machine STL may stop being a solid once written in single precision.
//!
//! A block is a SLIVER when
//!   1. its thickness (block_thickness(): the smallest mean chord length
//!      along the rows of its frame) is below `min_thickness`, and
//!   2. the model is thicker there: along the block's thinnest axis u, lines
//!      are cast through a grid over the block's footprint (num_lines x
//!      num_lines, at fixed irrational offsets inside the cells); each
//!      segment of a line inside the block lies in one segment of the line
//!      inside the input, and the model's thickness at the block is the mean
//!      length of those input segments (the block's own mean on the same
//!      lines is reported beside it). The model is thicker when that mean
//!      exceeds `min_thickness`.
//! A block thin where the model itself is that thin (a thin ear, a fin) is
//! not a sliver. Lines through a vertex or an edge (a 2D orientation of
//! exactly 0, CGAL exact predicate on the projected coordinates) or with an
//! odd number of crossings are dropped; when no line crosses the block, a
//! grid four times finer is tried, and if still none, the block is counted
//! as a sliver (undecided is not passed).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "subfab/mesh/mesh.h"
#include "subfab/validate/block_thickness.h"

namespace subfab {

//! One block to examine.
struct SliverBlock {
  const Mesh* mesh = nullptr;                           // closed solid, input coordinates
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();  // rotation input -> canonical (its machine frame)
};

//! Options of find_slivers().
struct SliverOptions {
  double min_thickness = 0.0;  // model units; blocks at least this thick are never slivers (must be > 0)
  int num_lines = 12;          // lines per side of the grid cast across a thin block (>= 1)
};

//! What find_slivers() measured on one block.
struct SliverMeasure {
  BlockThickness thickness;       // block_thickness() in the block's frame
  bool measured = false;          // lines were cast (only blocks thinner than min_thickness)
  std::size_t num_chords = 0;     // block segments found on the lines
  double block_chord = 0.0;       // their mean length (model units)
  double model_chord = 0.0;       // mean length of the input segments containing them (model units)
  bool sliver = false;
};

//! The sliver threshold of decompose's sliver stage and validate's check 9
//! (they must agree): max(floor, min(tolerance, max_height / 4)), model
//! units. `floor` is 1e-4 x the diagonal (where the model is thicker, no
//! block is thinner: thesis 4.3.4), the tolerance raises it (issue 17: no
//! block thinner than T). Capped at a quarter of the height limit: a block's
//! thickness is at most its mean chord along its milling direction, i.e. its
//! mean height, and a block filling the limit with a pointed or sloped top
//! has a mean height of H/3 (a cone) to H/2 (a wedge); at T near H every
//! block would be a "sliver" (egea at --max-height 0.1 --tolerance 8.3e-2:
//! T = 39.4 against H = 47.4, all 6 blocks 12.9 to 39 thick). H/4 keeps the
//! thin ones (a quarter of the allowed height on average) flagged.
//! max_height = infinity (no limit): max(floor, tolerance) as before.
double sliver_threshold(double floor, double tolerance, double max_height);

//! Measures every block (in parallel; the result does not depend on the
//! thread count). \throw InvalidArgumentError when min_thickness <= 0 or
//! num_lines < 1.
std::vector<SliverMeasure> find_slivers(const Mesh& input, const std::vector<SliverBlock>& blocks,
                                        const SliverOptions& options);

}  // namespace subfab
