// SPDX-License-Identifier: GPL-3.0-or-later
//! \file fill_deviation_lower_bound.h
//! A cheap, sound lower bound of the deviation FillDeviationMeter measures
//! exactly (measure_fill_deviation.h; issue 17): a screen that fails a
//! milled shape for sure before its costly exact measure.
//!
//! With S the input solid and F_k the milled shapes that stick out of it,
//! the model made is S' = S ∪ (∪ F_k). A point p of ∂F_k that lies outside
//! S and outside every other F_j (and not on one) lies on ∂S', so the
//! symmetric Hausdorff distance between ∂S' and ∂S is at least d(p, ∂S).
//! Such a point lies in F_k \ S, inside the fill of F_k (F_k \ the carved
//! block, which lies in S): in the region the exact measure of F_k covers,
//! so that measure (value within its error of the distance, accepted when
//! value + error <= T) fails whenever d(p, ∂S) > T. The other way, a
//! point x of ∂S inside F_k (buried by its fill) is at least d(x, ∂F_k)
//! from ∂S' (the open ball of that radius lies in F_k, so in the interior
//! of S'), and lies in the closure of F_k \ the carved block too. The
//! samples: the points of a barycentric grid of step 1/4 (15 per face) on
//! every face of F_k, and for the other way of S, meeting the boxes that
//! cover the fill (fill_columns()). Inside/outside of S and of the F_j is
//! exact (SolidIndex: the exact parity of a
//! ray's crossings, a point on the surface perturbed symbolically); a point
//! within 1e-7 x the largest coordinate of another F_j's surface counts as
//! on it (a contact face between two fills is inside S'), which only makes
//! the bound smaller. Distances: CGAL's AABB tree (doubles; a bound within
//! the rounding of a closest-point query).
#pragma once

#include <optional>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! Per filled block k, the largest d(p, ∂S) over its sampled points p of ∂S',
//! and d(x, ∂F_k) over the sampled points x of ∂S inside F_k (see the file
//! comment; 0 when none), model units. A block's search stops
//! once its bound exceeds `stop` (model units; +infinity: the maximum over
//! all its samples). Deterministic (a function of the meshes); parallel
//! over blocks.
//! \param solid  S: closed, outward-oriented, self-intersection-free solid
//! \param filled the milled shapes F_k that stick out of S (all of them: each is "another" for the rest)
//! \param fills  per filled block, boxes covering its fill (fill_columns()); nullopt: every face sampled
//! \param which  per filled block, whether to bound it (empty: all)
//! \param far    not null: per filled block, every sampled point whose
//!        distance exceeds `stop` (of ∂S' or of ∂S, see the file comment:
//!        where the block's fill makes the model deviate), the search then
//!        going on over all its samples instead of stopping; the caller
//!        locates a failure with them (decompose() lowers the allowances of
//!        the faces above them only)
std::vector<double> fill_deviation_lower_bounds(const Mesh& solid, const std::vector<const Mesh*>& filled,
                                                const std::vector<std::optional<std::vector<BoundingBox>>>& fills,
                                                double stop, const std::vector<char>& which = {},
                                                std::vector<std::vector<Vec3>>* far = nullptr);

}  // namespace subfab
