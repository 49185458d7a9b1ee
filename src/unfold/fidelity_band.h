// SPDX-License-Identifier: GPL-3.0-or-later
//! \file fidelity_band.h
//! Private: the fidelity band of the mask stage (apply_masks(), thesis
//! Section 3.3.1). Masks flip lattice signs to merge facets; left alone they
//! can move the surface far from the input (on bunny_lowres a thin ear was
//! eaten away, 6 grid spacings of Hausdorff distance). The band bounds both
//! directions of the Hausdorff distance:
//! - surface -> input: only points next to the ORIGINAL surface (a
//!   6-neighbour of the other sign, so closer than one spacing to the input)
//!   may flip; every vertex of the new surface is then within 1.5 spacings
//!   (apply_masks() keeps that rule);
//! - input -> surface (this file): the input is sampled (every triangle on a
//!   barycentric grid finer than half a spacing); for each sample x, K(x) is
//!   the set of lattice edges whose two ends lie within `radius` of x. A
//!   lattice edge with a sign change carries a vertex of the marching-cubes
//!   surface at its midpoint, inside the same ball, so while K(x) contains a
//!   sign change the surface passes within `radius` of x. A move is allowed
//!   only if every ball that contains a sign change keeps one.
//! Balls are deduplicated (samples with the same edge set are one
//! constraint); only the constraints that touch the flipped points are
//! re-evaluated, so a check costs a few hundred edge tests.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "subfab/geometry/classify_grid_points.h"
#include "subfab/mesh/mesh.h"

namespace subfab::unfold_detail {

class FidelityBand {
 public:
  FidelityBand() = default;
  //! Builds the constraints of `reference` (triangles, model units; need not
  //! be closed) on `grid` for the signs `inside` (grid.num_points() values).
  //! \param radius ball radius in grid spacings (> 0).
  FidelityBand(const Mesh& reference, const GridPoints& grid, const std::vector<std::uint8_t>& inside,
               double radius);

  bool empty() const { return offsets_.size() <= 1; }
  std::size_t num_constraints() const { return offsets_.empty() ? 0 : offsets_.size() - 1; }

  //! True if the signs `inside` (after a tentative flip of `flipped`) keep a
  //! sign change in every ball that had one before the flip.
  bool allows(const std::vector<std::uint8_t>& inside, const std::vector<std::size_t>& flipped) const;

  //! Records that `flipped` were flipped for good (`inside` is the new state).
  void commit(const std::vector<std::uint8_t>& inside, const std::vector<std::size_t>& flipped);

 private:
  int count_changes(const std::vector<std::uint8_t>& inside, std::size_t c) const;
  std::vector<std::uint32_t> touched(const std::vector<std::size_t>& flipped) const;

  std::array<std::size_t, 3> stride_{};
  // Constraint c's lattice edges (3 x point + axis): edges_[offsets_[c] .. offsets_[c + 1]).
  std::vector<std::size_t> offsets_;
  std::vector<std::uint64_t> edges_;
  std::vector<int> changes_;  // current number of sign changes per constraint
  // Constraints containing lattice point p: by_point_[point_offsets_[p] .. point_offsets_[p + 1]).
  std::vector<std::size_t> point_offsets_;
  std::vector<std::uint32_t> by_point_;
};

}  // namespace subfab::unfold_detail
