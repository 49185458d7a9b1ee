// SPDX-License-Identifier: GPL-3.0-or-later
//! \file tolerance_allowances.h
//! Which faces may lean past vertical in a decomposition within a tolerance
//! (issue 17, point 2; thesis Section 4.3.5 trades faithfulness for fewer
//! blocks). A face f facing away from an axis direction d (unit n.d < 0)
//! blocks every box for d that it meets: a 3-axis machine coming from +d
//! cannot remove the material under it. Within a tolerance T that material
//! may stay when it is thin: f is ALLOWED for d when the undercut depth
//! under it (UndercutDepth: the free length along -d below the face,
//! capped at the height limit and the model's extent, times |n.d|) is at
//! most depth_fraction x T. The stages then treat f as facing d (the
//! allowances travel as `allowed_overhangs` through field, grow, snap,
//! resolve and carve, like --max-overhang's angle), the carved blocks are
//! replaced by their milled shapes, and those are measured exactly
//! (mill_within_tolerance()): an allowance is only a proposal.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of tolerance_allowances().
struct ToleranceAllowanceOptions {
  double tolerance = 0.0;       // T, model units (> 0)
  double depth_fraction = 0.5;  // allow a face when its undercut depth <= this x T (unitless, > 0): below 1 it
                                // leaves room for where the fill reaches past the face's plane (a heuristic;
                                // the measure decides). decompose() starts at 2 and steps down per failing
                                // block (DecomposeOptions::tolerance_depth_fractions)
  double max_height = std::numeric_limits<double>::infinity();  // fills stop at the block's base: depth cap, model units
  Progress* progress = nullptr;  // info line (nullptr: silent)
};

//! Per face of `mesh`, bit k (k = 0, 1, 2) set when the face is allowed for
//! the axis along e_k it faces away from (see the file comment). Faces that
//! face every axis direction they meet get no bit. Deterministic and
//! independent of the thread count.
//! \param mesh closed, outward-oriented solid (canonical frame)
std::vector<std::uint8_t> tolerance_allowances(const Mesh& mesh, const ToleranceAllowanceOptions& options);

//! Per face of `mesh` and axis k, the undercut depth (UndercutDepth, model
//! units) under the face for the axis direction along e_k it faces away
//! from, capped as in tolerance_allowances(); +infinity where the face faces
//! every axis direction along e_k (no allowance needed, none given). Where
//! the depth exceeds depth_fraction x T its value is only known to exceed
//! it (the rays may stop early). The allowance bits at any fraction
//! q <= options.depth_fraction follow from it (allowances_at()).
std::vector<std::array<double, 3>> undercut_depths(const Mesh& mesh, const ToleranceAllowanceOptions& options);

//! Bit k of face f set when depths[f][k] <= fractions[level[f][k]] x
//! tolerance (levels at or past fractions.size() allow nothing): the
//! allowances of a decomposition round whose faces may stand at different
//! levels (decompose() lowers a face's level where a block fails).
std::vector<std::uint8_t> allowances_at(const std::vector<std::array<double, 3>>& depths,
                                        const std::vector<std::array<std::uint8_t, 3>>& level,
                                        const std::vector<double>& fractions, double tolerance);

//! Number of faces with at least one allowance.
std::size_t count_allowed_faces(const std::vector<std::uint8_t>& allowed);

//! Allowances decided per box (issue 17; bench/RESULTS.md, "Why the counts
//! are high", lead 1): a floor on the base of the boxes a face may lean in.
//! For face f facing away from d (d = -s e_k, s the exact sign of n_k), h_f
//! = max over its vertices of v.d and c = |n.d| (unit normal), the material
//! a block with base b (min of x.d over its box) leaves under f is at most
//! min(L_free, h_f - b) x c deep (L_free: the free length under f,
//! UndercutDepth). So at depth fraction q the face may lean in every box when
//! its undercut depth <= q T (floor -inf, allowances_at()), else in the boxes
//! whose base b >= h_f - q T / c (its floor). The stages take the floors
//! with the bits (SolidIndex): a box's validity and coverage compare its
//! actual base with them. Like the bits, a heuristic: the measure decides.
struct OverhangAllowances {
  std::vector<std::uint8_t> bits;             // per face: bit k set = allowed for the axis along e_k it faces
                                              // away from, in some box (the relaxed facing test of the field)
  std::vector<std::array<double, 3>> floors;  // per face and k: the base floor of bit k's allowance (d-coordinate,
                                              // model units; -inf: every box; unused where bit k is clear)
  bool operator==(const OverhangAllowances&) const = default;
};

//! allowances_at() with base floors (see OverhangAllowances): bit k of
//! face f is set when depths[f][k] <= q T (floor -inf) or, with
//! `with_floors`, whenever the face faces away from an axis along e_k
//! (floor h_f - q T / c), q = fractions[level[f][k]]; nothing past the last
//! level.
OverhangAllowances allowances_with_floors(const Mesh& mesh, const std::vector<std::array<double, 3>>& depths,
                                          const std::vector<std::array<std::uint8_t, 3>>& level,
                                          const std::vector<double>& fractions, double tolerance, double floor_scale);

//! Allowances of a uniform overhang angle (decompose()'s overhang ladder
//! within a tolerance, issue 17): bit k of face f set when the face faces
//! away from the axis direction d along e_k (exact sign of n_k) and leans at
//! most `max_overhang_deg` past vertical (unit n.d >= -overhang_sine(deg)),
//! in every box (floors -inf). What --max-overhang lets lean, as a proposal:
//! the blocks are milled and measured like any other allowance's.
//! \param max_overhang_deg in [0, 45]; 0 allows nothing
OverhangAllowances uniform_overhang_allowances(const Mesh& mesh, double max_overhang_deg);

//! Number of faces allowed to lean only above base floors: every axis with
//! an allowance has a finite floor (a face allowed in every box along some
//! axis is not counted, whatever its other axes' floors).
std::size_t count_floored_faces(const OverhangAllowances& allowances);

//! Number of faces whose allowance differs between `before` and `after`: a
//! bit set or cleared, or the floor of a set bit moved (a floor that only
//! rises shrinks the allowance without clearing a bit).
std::size_t count_changed_faces(const OverhangAllowances& before, const OverhangAllowances& after);

}  // namespace subfab
