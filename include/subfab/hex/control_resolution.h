// SPDX-License-Identifier: GPL-3.0-or-later
//! \file control_resolution.h
//! Resolution control, thesis Appendix D.5: more hexahedra across the thick
//! parts of a shape, fewer across its thin limbs, instead of the same
//! number of splits everywhere.
//!
//!   D.5.1 detect_cones(): on the coarse tubular structure, a tube
//!     hexahedron h whose two tube neighbours' facets opposite to h differ in
//!     area by more than `cone_ratio` (4: twice the resolution across) is a
//!     cone, its base on the larger side; only on terminal branches of the
//!     skeleton, at most `max_cones_per_branch` per branch (the largest
//!     ratios, never two neighbours);
//!   D.5.2 control_resolution(): on the padded structure, a cone is its tube
//!     layer (the core hexahedron and the four padding hexahedra on its
//!     sides). One integer variable per other ("regular") hexahedron, its
//!     number of regular 2 x 2 x 2 splits x >= 0; adjacent regular
//!     hexahedra split equally, across a cone the base side once more than
//!     the tip side; minimise the sum of x. Solved with COIN-OR CBC
//!     (deterministic, single thread). Cones only on terminal branches cut
//!     the mesh into a tree of parts, so the programme always has a
//!     solution;
//!   refine_hex_mesh(): the plan applied level by level (coarse to fine, every
//!     level conforming): with S levels in all, a regular hexahedron with x
//!     splits splits at each of the last x levels; a cone layer with tip
//!     splits x is replaced at level S - x (when its base side first splits)
//!     by the cone template, whose pieces then split with the tip side.
//!
//! The cone template (Figure D.6, 1x1 -> 2x2). Our padding layer exists
//! before the refinement (so that the coarse-to-fine optimisation starts from
//! a padded mesh), so a template must refine the padded cross-section, 5
//! quads (the core square and its ring of 4), into its regular split (20
//! quads) across one layer, every one of the 5 hexahedra going from a 1x1
//! tip face to a 2x2 base face. It does so in three sub-layers, one per
//! family of sheets of the cross-section (the chords through ring 0, core,
//! ring 2; through ring 3, core, ring 1; the ring loop): in each, every
//! quad that family crosses gets the 2D transition (a quad whose top is
//! split in two, in three quads around one inner vertex: bottom corner on
//! the unsplit side, side midpoint, top midpoint) extruded across, with the
//! split side turned towards ring 1 (first), ring 2 (second) or outwards
//! (third); ring 1 (ring 2) takes the sheet that leaves through that side as
//! a plain split into two sub-layers, and carries it to the boundary. 58
//! hexahedra. The sub-layers are as high as what they double (core width,
//! core width, padding thickness), and a 2D transition flatter than wide has
//! its inner point moved towards its unsplit side (at most to 0.3 of the
//! width). On an ideal layer (core square, padding to twice its width,
//! twice as high as wide) the worst piece has scaled Jacobian .17 (padding
//! trapezoids under the first transitions); on cactus after optimisation
//! .50. The 2x2 ->
//! 4x4 cone of Figure D.6 is the same template one level finer: the template
//! followed by one regular split of its pieces (the templates nest with the
//! regular splits, which keeps every level of the coarse-to-fine
//! optimisation conforming).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "subfab/hex/build_tubular_structure.h"
#include "subfab/hex/hex_mesh.h"
#include "subfab/hex/skeleton.h"

namespace subfab {

struct ResolutionControlOptions {
  double cone_ratio = 4.0;        // D.5.1: a cone when the opposite facets' areas differ by more than this factor
  int max_cones_per_branch = 2;   // D.5.1: per terminal branch, the largest ratios first (1x1->2x2 and 2x2->4x4)
  double time_limit_s = 10.0;     // D.5.2: CBC time limit, seconds (the programme is tiny: milliseconds)
};

//! A cone of the tubular structure (D.5.1).
struct Cone {
  int hex = -1;            // the tube hexahedron (index in the structure)
  int arc = -1;            // its arc (index in skeleton_arcs())
  double ratio = 0;        // area of the larger opposite facet / the smaller
  bool base_at_front = false;  // base on the side of the hexahedron's face 1 (corners 4..7), tip on face 0
};

//! Finds the cones of `structure`, built by build_tubular_structure() from
//! `skeleton` (whose arcs tell which branches are terminal), D.5.1. Sorted
//! by hexahedron. \throw InvalidArgumentError when the sizes do not match.
std::vector<Cone> detect_cones(const TubularStructure& structure, const Skeleton& skeleton,
                               const ResolutionControlOptions& options = {});

//! A cone's layer in the padded mesh.
struct ConeLayer {
  std::array<int, 5> hexes{};  // the core hexahedron, then the padding hexahedra on its sides c0c1, c1c2, c2c3, c3c0
  Quad tip{};                  // the core's tip corners c0..c3 (a cycle)
  Quad base{};                 // the core's base corners, b_i joined to c_i
  Quad outer_tip{}, outer_base{};  // the padding copies of tip and base (outer_tip[i] joined to tip[i])
};

//! The resolution of every hexahedron of the padded structure (D.5.2).
struct ResolutionPlan {
  std::vector<int> splits;      // per hexahedron: regular splits x; in a cone layer, those of its tip side
  std::vector<int> layer_of;    // per hexahedron: index in `layers`, or -1
  std::vector<ConeLayer> layers;
  std::size_t num_cones_found = 0;  // given to control_resolution()
  std::size_t num_variables = 0;    // of the integer programme (the regular hexahedra)
  std::size_t num_constraints = 0;
  double ilp_seconds = 0;
  bool solved = true;               // false: CBC found no solution; then no cone is used (all x = 0)
};

//! Builds the cone layers of `cones` in `padded` (the structure after
//! pillow_hex_mesh(): its first hexahedra are the structure's) and solves
//! the integer programme of D.5.2. Without cones every x is 0.
//! \throw InvalidArgumentError when a cone is not a tube hexahedron with
//! four padded sides.
ResolutionPlan control_resolution(const HexMesh& padded, const std::vector<Cone>& cones,
                                  const ResolutionControlOptions& options = {});

//! Number of hexahedra the plan gives with `offset` more regular splits
//! everywhere (the template has 58 hexahedra).
std::size_t planned_num_hexes(const ResolutionPlan& plan, int offset);

//! Per hexahedron of a mesh being refined: the level at which it splits
//! (regular) or is replaced by its cone template, and its cone layer slot.
struct RefinementSchedule {
  std::vector<int> first_level;  // levels are 1, 2, ...; a hexahedron splits at every level >= this
  std::vector<int> cone_slot;    // -1, or 5 x layer + position in ConeLayer::hexes
  std::vector<int> template_of;  // -1, or the layer whose template this hexahedron is (a piece of)
  std::vector<ConeLayer> layers;
};

//! The schedule of `plan` with `offset` more splits everywhere: returns it
//! and sets `num_levels` (the largest x + offset).
RefinementSchedule schedule_refinement(const ResolutionPlan& plan, int offset, int& num_levels);

//! One level of the refinement: every hexahedron whose first level is <=
//! `level` is split 2 x 2 x 2 (children keep its first level), every cone
//! layer whose level it is gets its template (children split from the next
//! level on), the others are copied. Old vertices keep their indices; new
//! ones are placed by trilinear interpolation. `schedule` is updated to the
//! new mesh. When every hexahedron splits the result is subdivide_hex_mesh().
//! `axes`, if given (one per hexahedron), says along which local axes each
//! regular hexahedron splits (see layer_keeping_axes(): it must be the same
//! for every hexahedron of a sheet, so that the level stays conforming).
HexMesh refine_hex_mesh(const HexMesh& mesh, RefinementSchedule& schedule, int level,
                        const std::vector<std::array<bool, 3>>* axes = nullptr);

//! The finest level keeping the tubes' layers (not in the thesis; issue 14,
//! docs/hexmesh.md "4c"): the axes along which each hexahedron of `mesh`
//! splits at `level` (for refine_hex_mesh()). A sheet (hex_sheets()) is
//! left whole when at least `min_share` of its hexahedra have an irregular
//! interior edge along its axis (sheet_irregularity(): a tube's layer,
//! whose hexahedra all touch the valence-3 edges of its core's corners) and
//! every one of its hexahedra splits regularly at `level`; every other axis
//! splits. `num_kept`, if given, gets the sheets left whole.
std::vector<std::array<bool, 3>> layer_keeping_axes(const HexMesh& mesh, const RefinementSchedule& schedule, int level,
                                                    double min_share, std::size_t* num_kept = nullptr);

//! The hexahedra of `plan` with `offset` (schedule_refinement()) when its
//! finest level keeps the layers (layer_keeping_axes()): the levels applied
//! to the topology of `padded` (the positions do not matter), exact.
std::size_t num_hexes_keeping_layers(const HexMesh& padded, const ResolutionPlan& plan, int offset, double min_share);

}  // namespace subfab
