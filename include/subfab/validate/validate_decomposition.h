// SPDX-License-Identifier: GPL-3.0-or-later
//! \file validate_decomposition.h
//! Checkers for a height-field block decomposition (thesis Section 4.2, the
//! six validity conditions), usable on their own by tests and users and
//! together by validate_decomposition() (`subfab validate`):
//!   1. every block is a closed, oriented 2-manifold with positive volume that
//!      does not intersect itself (exact; the booleans of 3, 4 and 10 need it);
//!   2. height field: every face whose unit normal n has n.d < -1e-3 lies on
//!      the block's base plane (all its vertices at the minimum of v.d);
//!   3. no two blocks overlap (exact intersection volume <= 1e-6 of the smaller);
//!   4. every block lies inside the input (exact volume outside <= 1e-6 of the block);
//!   5. coverage: area-weighted samples of the input surface lie within
//!      1e-5 x bbox diagonal of some block's boundary;
//!   6. height and machine-size limits hold;
//!   7. each machine mesh is its block moved rigidly (direction to +Z, base on z = 0);
//!   8. each machine mesh, in single precision (as binary STL stores it), is
//!      still a closed solid without zero-area faces or self-intersections
//!      (check_single_precision.h);
//!   9. no slivers: no block thinner than max(1e-4 x diagonal, min(T, H / 4)) (H the height limit) where the
//!      model is thicker (find_slivers.h; T = the tolerance, 0 when exact);
//!  10. (decompositions within a tolerance T only) the model made, the input
//!      with the blocks that stick out of it, lies within T of the input:
//!      symmetric Hausdorff distance between the surfaces <= T (checks 4 and
//!      5 then accept blocks sticking out and samples within T); measured in
//!      decompose's working frame on the frame blocks when the folder has
//!      them (match_frame_blocks.h), else on the exported blocks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/mesh/mesh.h"
#include "subfab/validate/find_slivers.h"
#include "subfab/validate/milled_shape.h"

namespace subfab {

// ---------------------------------------------------------------- check 1
//! Topology and volume of one block.
struct SolidReport {
  std::size_t num_faces = 0;
  std::size_t num_boundary_edges = 0;       // directed edges without an opposite twin
  std::size_t num_non_manifold_edges = 0;   // undirected edges with more than 2 faces, or
                                            // used twice in the same direction (orientation flip)
  std::size_t num_non_manifold_vertices = 0;  // vertices whose faces form more than one fan
  std::size_t num_degenerate_faces = 0;     // zero-area faces (reported, not a failure)
  double volume = 0.0;                      // signed volume (model units^3)
  bool ok() const {
    return num_faces > 0 && num_boundary_edges == 0 && num_non_manifold_edges == 0 &&
           num_non_manifold_vertices == 0 && volume > 0.0;
  }
};

//! Checks that `block` is a closed, consistently oriented 2-manifold with
//! positive volume (combinatorial check on the indexed faces).
SolidReport check_closed_solid(const Mesh& block);

// ---------------------------------------------------------------- check 2
//! Options of check_height_field().
struct HeightFieldOptions {
  double normal_tolerance = 1e-3;  // faces with unit n.d below -this must lie on the base (unitless)
  double plane_tolerance = 0.0;    // max |v.d - base| of a base vertex (model units; 0 = 1e-9 x block size)
};

//! Result of check_height_field().
struct HeightFieldReport {
  double base = 0.0;                 // min over vertices of v.d (model units)
  double height = 0.0;               // max - min of v.d (model units)
  std::size_t num_overhang_faces = 0;  // faces facing away from d that are not on the base
  double worst_cosine = 0.0;         // most negative n.d among those faces (0 if none)
  double steepest_cosine = 0.0;      // most negative n.d among all faces off the base, within the
                                     // tolerance or not (0 if none): how far the block overhangs
  bool ok() const { return num_overhang_faces == 0; }
};

//! Height-field test along the unit milling direction `direction` (the tool
//! comes from +direction; the base faces -direction), thesis Section 4.2.
HeightFieldReport check_height_field(const Mesh& block, const Vec3& direction,
                                     const HeightFieldOptions& options = {});

//! Degrees past vertical of a face whose unit normal n has n.d = `cosine`
//! (asin(-cosine); 0 when the face does not face away, cosine >= 0).
double overhang_angle_deg(double cosine);

//! Check 2's cosine tolerance for blocks made under an overhang allowance of
//! `max_overhang_deg` degrees (decompose's --max-overhang): 1e-3 (the margin
//! for the rounding of exact blocks to doubles) + overhang_sine(deg).
double height_field_normal_tolerance(double max_overhang_deg);

//! True when check_height_field() finds no overhang.
bool is_height_field(const Mesh& block, const Vec3& direction, const HeightFieldOptions& options = {});

// ------------------------------------------------------------ checks 3, 4
//! Volume of the intersection of two closed solids, computed with exact
//! booleans (CGAL corefinement on an exact kernel; Nef polyhedra when the
//! solids touch so that no corefinement result is a 2-manifold). 0 when
//! their bounding boxes do not overlap. \throw AlgorithmError if a block has
//! degenerate faces or self-intersects.
double blocks_overlap(const Mesh& a, const Mesh& b);

//! Which boolean nef_boolean_volume() measures.
enum class NefBoolean { Intersection, Difference };

//! vol(a ∩ b) or vol(a \ b) of two closed solids on exact Nef polyhedra
//! (CGAL Nef_polyhedron_3, regularized): much slower than the corefinement,
//! but defined when the result is not a 2-manifold (solids touching along an
//! edge or at a point). The fallback of blocks_overlap() and volume_outside().
double nef_boolean_volume(const Mesh& a, const Mesh& b, NefBoolean op);

//! A rigorous upper bound of the volume of the intersection of two solids
//! (closed meshes): the volume of the intersection of their extents along
//! the three rows of `frame` (a rotation; +infinity if it is not one), with
//! the rounding of the dot products accounted for. 0 when a row separates
//! them. Blocks that meet on a plane of the frame get a bound of the order
//! of the rounding error, which settles the pair without a boolean.
double overlap_volume_bound(const Mesh& a, const Mesh& b, const Eigen::Matrix3d& frame);

//! Volume of `block` outside the closed solid `solid` (exact booleans, with
//! the same Nef fallback as blocks_overlap()).
//! \throw AlgorithmError if a mesh has degenerate faces or self-intersects.
double volume_outside(const Mesh& block, const Mesh& solid);

// ---------------------------------------------------------------- check 5
//! Options of surface_coverage().
struct CoverageOptions {
  std::size_t num_samples = 20000;  // area-weighted samples of the input surface (plus every vertex)
  double tolerance = 0.0;           // max distance to a block boundary (model units; 0 = 1e-5 x diagonal)
  std::uint64_t seed = 1;           // sampling seed (results are deterministic)
};

//! Result of surface_coverage().
struct CoverageReport {
  std::size_t num_samples = 0;
  std::size_t num_uncovered = 0;  // samples farther than the tolerance from every block
  double max_distance = 0.0;      // largest sample distance to the blocks (model units)
  double tolerance = 0.0;         // the tolerance used (model units)
  Vec3 worst_point = Vec3::Zero();
  bool ok() const { return num_samples > 0 && num_uncovered == 0; }
};

//! Samples the surface of `input` (area-weighted, deterministic) and measures
//! each sample's distance to the union of the block surfaces (AABB tree).
CoverageReport surface_coverage(const Mesh& input, const std::vector<const Mesh*>& blocks,
                                const CoverageOptions& options = {});

// ----------------------------------------------------------- all checks
//! One block as exported (input coordinates).
struct ValidationBlock {
  Mesh mesh;                              // the block, input coordinates
  Vec3 direction = Vec3::UnitZ();         // unit milling direction, input coordinates
  std::optional<Mesh> machine_mesh;       // the exported machine mesh, if any
  Eigen::Matrix4d machine_transform = Eigen::Matrix4d::Identity();  // input -> machine coordinates
  std::optional<Mesh> frame_mesh;         // the block as decompose holds it in its working frame
                                          // (OUTDIR/frame/, within a tolerance; match_frame_blocks.h)
};

//! Limits the decomposition was asked to respect (model units).
struct ValidationLimits {
  double max_height = std::numeric_limits<double>::infinity();  // block height along its direction
  std::optional<Vec3> machine;  // work volume X, Y, Z; Z along the milling direction
};

//! Options of validate_decomposition().
struct ValidationOptions {
  double normal_tolerance = 1e-3;     // check 2 (unitless cosine)
  double overlap_tolerance = 1e-6;    // check 3: overlap volume / smaller block volume
  double outside_tolerance = 1e-6;    // check 4: volume outside / block volume
  std::size_t num_coverage_samples = 20000;  // check 5
  double coverage_tolerance = 1e-5;   // check 5: distance / bbox diagonal
  double limit_tolerance = 1e-6;      // check 6 and 7: slack / bbox diagonal
  double sliver_thickness = 1e-4;     // check 9: blocks thinner than max(this x diagonal, tolerance)
                                      // where the model is thicker are slivers (fraction of the diagonal)
  std::optional<double> sliver_tolerance;  // check 9's tolerance (model units) when not `tolerance` (the one
                                      // the blocks were made within, where `tolerance` adds a recorded
                                      // deviation of the decomposed model: `validate --against-input`)
  ValidationLimits limits;            // check 6
  double tolerance = 0.0;             // deviation allowed (model units; the decomposition's --tolerance):
                                      // when > 0, blocks may stick out of the input (check 4 lists them),
                                      // check 5 accepts samples within it, and check 10 measures the model
                                      // made (input ∪ blocks) against the input: symmetric Hausdorff
                                      // distance between the surfaces (FillDeviationMeter) <= it
  double tolerance_error = 0.02;      // check 10: error bound of the distances, fraction of the tolerance
  std::optional<Eigen::Matrix3d> frame_rotation;  // checks 3, 4, 10: decompose's frame (decomposition.json
                                      // "rotation", canonical = rotation x input). Set, with a tolerance, and every
                                      // block with its frame_mesh: check 10 measures the frame blocks against the
                                      // input turned as decompose turned it, the rounding back to the exported
                                      // blocks added to the bound, and checks 3 and 4 run their exact booleans on
                                      // the frame blocks, their volumes bounded back the same way
                                      // (match_frame_blocks.h; refused frame blocks fail check 10). Unset, or a
                                      // block without one (folders written before the frame blocks): the exported
                                      // blocks against the input (slow on turned models)
  double frame_snap_tolerance = 1e-9;  // rotate_into_frame()'s snapping (decomposition.json "frame"."snap_tolerance")
  bool measure_milled_shapes = true;  // informational: each block's milled shape (milled_shape.h)
  double milled_hausdorff_error = 1e-5;  // error bound of its distances (fraction of the diagonal)
  Progress* progress = nullptr;       // progress per check (nullptr: silent)
};

//! Outcome of one of the checks.
struct CheckReport {
  std::string name;                   // "closed solid", "height field", ...
  bool passed = true;
  std::string summary;                // one line: what was measured
  std::vector<std::string> failures;  // one line per failing item (at most 20 kept)
  std::size_t num_failures = 0;       // all failing items
};

//! Outcome of validate_decomposition().
struct ValidationReport {
  std::vector<CheckReport> checks;  // the checks, in order (9; 10 with a tolerance)
  MilledShapesReport milled;        // informational, not a check (empty when not measured)
  std::vector<SliverMeasure> slivers;  // check 9: every block's thickness (and the model's, for thin ones)
  double sliver_thickness = 0.0;    // check 9's threshold (model units)
  // check 10 (tolerance > 0): the deviation of the model made, model units
  std::size_t num_filled = 0;       // blocks that stick out of the input
  std::size_t num_bounded_by_parts = 0;  // of those, cleared by the bound over their parts' surfaces
                                         // (fill_deviation_upper_bound.h), not measured in regions
  double volume_sticking_out = 0.0; // volume of the blocks outside the input, summed (model units^3; check 4)
  double deviation_to_input = 0.0;  // how far the blocks stick out (max over the filled blocks)
  double deviation_from_input = 0.0;  // how deep the input surface lies under them
  double deviation_error = 0.0;     // error bound of both (with the frame's rounding when measured in it)
  bool measured_in_frame = false;   // check 10 measured the frame blocks in decompose's frame
  double frame_rounding = 0.0;      // then: FrameMatch::rounding(), part of deviation_error (model units)
  bool passed() const {
    for (const CheckReport& c : checks)
      if (!c.passed) return false;
    return !checks.empty();
  }
};

//! Runs the checks on a decomposition of `input` (thesis Section 4.2).
//! Pairwise overlaps use exact booleans only for pairs whose bounding boxes
//! overlap and whose overlap_volume_bound() (input frame, or either block's
//! machine frame) exceeds the tolerance. Then, unless turned off, measures
//! every block's milled shape (measure_milled_shapes(), informational: it
//! never fails the validation).
ValidationReport validate_decomposition(const Mesh& input, const std::vector<ValidationBlock>& blocks,
                                        const ValidationOptions& options = {});

}  // namespace subfab
