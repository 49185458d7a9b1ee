// SPDX-License-Identifier: GPL-3.0-or-later
//! \file compute_field.h
//! The solution-space fields of box growth (thesis Section 4.3.2, "Solution
//! space"): one scalar field per milling direction on a regular grid of points
//! over the padded bounding box, with values
//! - Forbidden (thesis: +infinity) at the 8 corners of every closed grid cell
//!   that meets a triangle facing away from the direction (n.d < 0), and at
//!   points inside the solid deeper than the height limit;
//! - Good (thesis: -1) at the other corners of cells that meet triangles, all
//!   of them facing the direction (n.d >= 0);
//! - Free (thesis: 0) everywhere else.
//!
//! Outline of compute_fields():
//!   1. grid = make_grid(mesh)
//!   2. for every triangle (in parallel): the exact sign of each component of
//!      its normal, and the closed grid cells it meets (exact test);
//!      OR the per-cell flags (order independent, so thread-count independent)
//!   3. exact inside/outside of every grid point (parity of exact crossings
//!      along grid lines, symbolic perturbation for degenerate cases);
//!      exit distances along +-x, +-y, +-z when a height limit is set
//!   4. per direction: point values from the flags of the 8 cells around each
//!      point and the depth, then 3D prefix sums for O(1) box counts.
//!
//! Conventions decided here (tests check them):
//! - A triangle "faces" direction d when the exact sign of n.d is >= 0, where
//!   n = (b - a) x (c - a) is evaluated exactly. Triangles parallel to d
//!   (n.d == 0: walls a 3-axis tool reaches from the side) face d, so they are
//!   Good for both +d and -d. A degenerate (zero-area) triangle faces every
//!   direction.
//! - Cells are closed: a triangle touching a cell only on its boundary still
//!   marks the cell's corners.
//! - Hence: a box spanning grid points lo..hi with count_forbidden(lo, hi) == 0
//!   meets no triangle facing away from the direction, not even on its
//!   boundary (such a triangle meets a closed cell that shares at least a
//!   corner with the box, and all 8 corners of that cell are Forbidden).
//! - Inside/outside of a grid point p is that of p + (e, e^2, e^3) for an
//!   infinitesimal e > 0 (simulation of simplicity): a point exactly on the
//!   surface is classified consistently, as the point infinitesimally beside it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/geometry/axis.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! A regular grid of points over the padded bounding box (canonical frame).
struct GridGeometry {
  Vec3 origin = Vec3::Zero();           // position of point (0,0,0), model units
  double spacing = 0;                   // distance between neighbouring points, model units
  std::array<int, 3> num_points{0, 0, 0};  // points per axis

  //! Position of point (i, j, k): origin + spacing * (i, j, k), evaluated
  //! component-wise as origin[c] + spacing * index (the one definition every
  //! stage must use).
  Vec3 point(int i, int j, int k) const {
    return Vec3(coordinate(0, i), coordinate(1, j), coordinate(2, k));
  }
  //! Coordinate of grid plane `index` along dimension `dim` (0, 1, 2).
  double coordinate(int dim, int index) const { return origin[dim] + spacing * index; }
  //! Linear index of point (i, j, k): i + nx * (j + ny * k).
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(num_points[0]) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(num_points[1]) * static_cast<std::size_t>(k));
  }
  //! Largest index i in [0, n) with coordinate(dim, i) <= x, or -1 if none
  //! (exact with respect to coordinate()).
  int index_at_or_below(int dim, double x) const;
  //! Smallest index i in [0, n) with coordinate(dim, i) >= x, or n if none.
  int index_at_or_above(int dim, double x) const;
  //! Total number of points.
  std::size_t num_total_points() const {
    return static_cast<std::size_t>(num_points[0]) * static_cast<std::size_t>(num_points[1]) *
           static_cast<std::size_t>(num_points[2]);
  }
};

//! Grid spacing = average edge length x grid_factor; padding = 1 cell around
//! the bounding box (the outermost points lie at least one spacing outside it).
//! \throw InvalidMeshError if the mesh has no faces or zero extent.
//! \throw InvalidArgumentError if grid_factor <= 0 or the grid would exceed
//!        2^31 points (increase grid_factor).
GridGeometry make_grid(const Mesh& mesh, double grid_factor = 1.0);

//! Field value at a grid point (thesis: -1, 0, +infinity).
enum class FieldValue : std::int8_t { Good = -1, Free = 0, Forbidden = 1 };

//! The field of one milling direction.
struct HeightField {
  Axis axis = Axis::PosZ;
  GridGeometry grid;
  std::vector<FieldValue> values;  // per grid point, indexed by grid.index(i, j, k)

  //! Number of Forbidden (resp. Good) points with lo[c] <= index[c] <= hi[c]
  //! for c = 0, 1, 2 (inclusive range of grid-point indices). O(1) via 3D
  //! prefix sums. Ranges are clamped to the grid; an empty range gives 0.
  std::int64_t count_forbidden(const std::array<int, 3>& lo, const std::array<int, 3>& hi) const;
  std::int64_t count_good(const std::array<int, 3>& lo, const std::array<int, 3>& hi) const;

  //! (Re)builds the prefix tables from `values` (compute_fields calls it;
  //! call it again after editing values by hand).
  void build_prefix_sums();

  //! 3D prefix tables of size (nx+1)(ny+1)(nz+1): entry (i, j, k) counts the
  //! points with indices < (i, j, k). Stored modulo 2^32 (exact for grids
  //! below 2^32 points).
  std::vector<std::uint32_t> prefix_forbidden;
  std::vector<std::uint32_t> prefix_good;
};

//! Options of compute_fields().
struct FieldOptions {
  double grid_factor = 1.0;  // grid spacing = average edge length x grid_factor (> 0)
  double max_height = std::numeric_limits<double>::infinity();  // block height limit, model units (infinite = none)
  double max_overhang_deg = 0.0;  // faces may lean this far past vertical and count as facing the axis (degrees,
                                  // [0, 45], see overhang_sine(); 0 = exact height fields)
  const std::vector<std::uint8_t>* allowed_overhangs = nullptr;  // per face of the mesh passed: bit k set = the
                                  // face counts as facing both +-e_k (decompose --tolerance: its undercut is within
                                  // the tolerance, tolerance_allowances()); nullptr = none
  Progress* progress = nullptr;  // info lines (grid size); the caller opens the stage (nullptr = silent)
};

//! The six fields (index = axis_index(axis)), sharing one grid and one exact
//! inside/outside classification (thesis Section 4.3.2, Figure 4.3).
//! Height limit: a grid point p strictly inside the solid is Forbidden for
//! direction d when the ray p + t d (t > 0) leaves the solid only at
//! t > max_height (it cannot lie under a top surface within max_height).
//! Deterministic and independent of the thread count.
//! \param mesh a closed, consistently outward-oriented triangle mesh (canonical frame)
//! \throw InvalidMeshError / InvalidArgumentError as make_grid; InvalidArgumentError
//!        if max_height <= 0 or NaN.
std::array<HeightField, 6> compute_fields(const Mesh& mesh, const FieldOptions& options);

//! The same on a given grid (options.grid_factor is ignored): for recomputing
//! the fields of a locally refined mesh on the grid of the original one, or
//! for tests on hand-made grids. The grid must have at least 2 points per axis.
std::array<HeightField, 6> compute_fields(const Mesh& mesh, const GridGeometry& grid, const FieldOptions& options);

}  // namespace subfab
