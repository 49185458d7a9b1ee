// SPDX-License-Identifier: GPL-3.0-or-later
//! \file orient_mesh.h
//! Orientation of the input before decomposition (thesis Section 4.3.1): the
//! rotation R minimising the area-weighted L1 norm of the rotated normals,
//!   E(R) = sum_f A_f ||R n_f||_1 / sum_f A_f        (n_f unit normal, A_f area),
//! so that as much of the surface as possible faces a major axis. E >= 1, with
//! equality iff every normal is axis-aligned.
//!
//! Outline of orient_mesh() (the authors searched only the new Z axis over
//! 1000 directions; we search all three rotational degrees of freedom):
//!   1. area-weighted normals; a clustered copy (normals binned on a cube map)
//!      for the coarse search;
//!   2. coarse search over a fundamental region of SO(3) modulo the 24 cube
//!      rotations (E is invariant under them): the new Z axis over
//!      spherical-Fibonacci directions with z >= 1/sqrt(3), times twists about
//!      it over [0, 90 deg); in parallel;
//!   3. Nelder-Mead refinement of the best distinct candidates (and of the
//!      identity) on the exact energy, in rotation-vector coordinates: the
//!      distinct local optima found, plus the input frame, are the candidate
//!      frames (each reduced by the cube symmetries to the one closest to the
//!      identity, so an exact 90-degree relabelling never turns the model);
//!   4. preference order: by energy, but the input frame ranks ahead of any
//!      frame that does not lower E by more than min_relative_gain (a tiny
//!      turn gains nothing measurable and tilts every axis-aligned face and
//!      edge of the input, which exact validity then pays for in refinement
//!      and slivers), and ahead of everything for a CAD part modelled in its
//!      axes (see OrientOptions::keep_frame_area);
//!   5. feasibility (find_infeasible_features.h): the first candidate in
//!      preference order whose frame has no crease or corner that no
//!      axis-aligned height-field box can cover (with the input's own
//!      coordinate rounding snapped when only that makes it feasible:
//!      OrientOptions::precision_snap_tolerance);
//!   6. if every candidate has some (typical of CAD parts with sharp oblique
//!      creases: the energy optima put a crease where no axis sees both of
//!      its faces), the coarse frames of step 2 are tested in order of
//!      energy, in parallel batches, until one is feasible (at most
//!      `feasibility_budget` face tests in all); the first feasible one is
//!      refined locally on the exact energy, every step kept feasible
//!      (exact test). If none is found, the candidate with the fewest
//!      features (the caller then repairs them or fails early).
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/fidelity/find_infeasible_features.h"
#include "subfab/geometry/rotate_into_frame.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of orient_mesh().
struct OrientOptions {
  int num_directions = 2000;  // spherical-Fibonacci samples of the new Z axis over the whole sphere (about 1/4 used, by symmetry)
  int num_twists = 24;        // samples of the twist about the new Z axis over [0, 90 deg)
  int num_refined = 8;        // best distinct coarse candidates refined locally
  double tolerance = 1e-10;   // refinement stops when the simplex is smaller than this (radians)
  // The input frame is preferred to any frame that does not lower E by more
  // than this fraction. Organic models gain 0.1-0.3% from a turn of a few
  // degrees (spot, bunny, elephant, bob), which is within the noise of the
  // block count (spot: 67 blocks in its frame, 80 turned by 5.6 degrees for
  // 0.2%); the thesis's own inputs (moai, cube spike, airplane) gain < 0.05%.
  // 0 = pure minimum.
  double min_relative_gain = 0.01;  // relative energy
  // An input modelled in its axes (CAD) is kept in its frame: when at least
  // keep_frame_area of the surface area has normals exactly on an axis and the
  // input's energy is within keep_frame_tolerance (relative) of the best found.
  // (Turning such a part by a fraction of a degree lowers E slightly but tilts
  // its flat faces off the axes, which costs blocks.)
  double keep_frame_area = 0.1;        // fraction of the surface area, in [0, 1]
  double keep_frame_tolerance = 0.02;  // relative energy
  // After a turn, vertex coordinates closer than this along an axis are made
  // equal: the turn's rounding (and the optimiser's ~1e-10 rad accuracy)
  // would otherwise tilt, by a hair, faces and edges the new frame makes
  // axis-aligned, and exact validity sees any tilt (a turned-back box would
  // need many blocks, or none would fit its corners).
  double snap_tolerance = kFrameSnapTolerance;  // 1e-9: fraction of the bounding-box diagonal (0 = no snapping)
  // The input's own coordinate rounding, as a snap (fraction of the diagonal;
  // decompose() sets 4 x coordinate_rounding() / diagonal, the most two points
  // of one plane of the designer's model can differ along an axis after the
  // turn). A candidate frame that snap_tolerance leaves with infeasible
  // features is tested again with this snap (when larger), and kept with it
  // when that makes it feasible: its infeasibility was the file's rounding
  // (pinion.off, 6 digits: 872 exact blocks in a worse frame, 1 here). 0 = off.
  double precision_snap_tolerance = 0;
  // A CAD part exported at an angle: the frame of its largest flat faces
  // (z along the normal direction holding the most area, x along the largest
  // perpendicular one; directions within this angle, radians, are one) is a
  // candidate, preferred like an input modelled in its axes (keep_frame_area,
  // keep_frame_tolerance) when that much area is then exactly on the axes
  // (with the precision snap). The energy optimum can lie a few degrees off it
  // (an oblique fandisk: 3 degrees about x, 0.3% lower energy, 15 exact blocks
  // instead of its own frame's 11). 0 = no such candidate.
  double design_frame_angle = 1e-4;
  int num_candidates = 6;       // best distinct local optima refined exactly and ranked (besides the input frame)
  bool check_feasibility = true;  // skip candidate frames with infeasible creases/corners (find_infeasible_features)
  // Step 6: number of face tests (frames x faces of the exact feasibility
  // test) spent searching the coarse frames for a feasible one when no
  // candidate is; the exact test runs at roughly 1e5 faces per second per
  // core, so the default costs at most about 5-10 s on 2 cores. 0 = no search.
  double feasibility_budget = 1e6;
  // Exact-energy evaluations refining the frame found in step 6, each with
  // an exact feasibility test (at most a quarter of the budget; 0 = none).
  int feasibility_refine_evals = 120;
  Progress* progress = nullptr;  // info line with the energies (nullptr = silent)
};

//! One candidate frame of orient_mesh(), in preference order.
struct OrientCandidate {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // canonical = rotation * input
  double energy = 0;          // E(rotation)
  bool input_frame = false;   // the identity (the input's own frame)
  long num_infeasible = -1;   // infeasible edges + vertices in this frame (-1: not checked)
  double snap_tolerance = 0;  // the snap the frame's check used (OrientOptions::snap_tolerance or precision_snap_tolerance)
  bool design_frame = false;  // the frame of the largest flat faces (OrientOptions::design_frame_angle)
};

//! Result of orient_mesh().
struct OrientResult {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // proper rotation; canonical = rotation * input
  double energy_before = 0;  // E(identity)
  double energy_after = 0;   // E(rotation); <= energy_before unless a better frame was infeasible
  std::vector<OrientCandidate> candidates;  // every candidate frame, in preference order
  std::size_t chosen = 0;        // index of the chosen candidate
  std::size_t num_rejected = 0;  // candidates with infeasible features ahead of the chosen one (all when none is free of them)
  std::size_t num_searched = 0;  // coarse frames tested in step 6 (0 when a candidate was feasible)
  bool found_by_search = false;  // the chosen frame comes from step 6 (it is the last candidate)
  FeasibilityResult infeasible;  // infeasible features of the chosen frame (empty when feasible or unchecked)
  double snap_tolerance = 0;     // rotate_into_frame()'s snap for the chosen frame (precision_snap_tolerance when
                                 // only that made it feasible, else snap_tolerance)
};

// rotate_into_frame() (the mesh in a frame, as decompose() turns it): subfab/geometry/rotate_into_frame.h

//! Fraction of the area of `mesh` whose normals lie exactly on an axis (two
//! components of the computed normal zero, as orient_mesh() tests the input
//! frame): at least OrientOptions::keep_frame_area for a part drawn in this frame.
double axis_aligned_area_fraction(const Mesh& mesh);

//! E(R) above for the mesh's faces (zero-area faces contribute nothing).
//! \throw InvalidMeshError if the total area is zero.
double orientation_energy(const Mesh& mesh, const Eigen::Matrix3d& rotation);

//! Finds the rotation minimising E (thesis Section 4.3.1, all three degrees of
//! freedom) among frames where an exact height-field decomposition is
//! possible (see the file comment, steps 4-5). Deterministic and independent
//! of the thread count. Returns exactly the identity when the input frame is
//! preferred (OrientOptions::min_relative_gain, keep_frame_area) and feasible.
//! \param mesh closed, consistently oriented mesh (#V vertices, #F faces)
//! \throw InvalidMeshError if the mesh has no faces or zero area;
//!        InvalidArgumentError if an option is out of range.
OrientResult orient_mesh(const Mesh& mesh, const OrientOptions& options = {});

}  // namespace subfab
