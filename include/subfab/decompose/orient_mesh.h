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
//!      identity) on the exact energy, in rotation-vector coordinates;
//!   4. the identity when the best energy is not lower by more than
//!      min_relative_gain; else among results within 1e-9 (relative) of the best energy, the one
//!      closest to the identity (after reduction by the cube symmetries), so
//!      already axis-aligned models keep exactly their frame; the identity
//!      also when the input is a CAD part modelled in its axes (see
//!      OrientOptions::keep_frame_area).
#pragma once

#include <Eigen/Core>

#include "subfab/core/progress.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of orient_mesh().
struct OrientOptions {
  int num_directions = 2000;  // spherical-Fibonacci samples of the new Z axis over the whole sphere (about 1/4 used, by symmetry)
  int num_twists = 24;        // samples of the twist about the new Z axis over [0, 90 deg)
  int num_refined = 8;        // best distinct coarse candidates refined locally
  double tolerance = 1e-10;   // refinement stops when the simplex is smaller than this (radians)
  // The input frame is kept unless the best rotation lowers E by more than
  // this fraction: a model already oriented by its author (the thesis's own
  // inputs: moai, cube spike, airplane) gains < 0.05% from a turn of about
  // half a degree, which is not worth leaving the user's frame. 0 = pure minimum.
  double min_relative_gain = 1e-3;  // relative energy
  // An input modelled in its axes (CAD) is kept in its frame: when at least
  // keep_frame_area of the surface area has normals exactly on an axis and the
  // input's energy is within keep_frame_tolerance (relative) of the best found.
  // (Turning such a part by a fraction of a degree lowers E slightly but tilts
  // its flat faces off the axes, which costs blocks.)
  double keep_frame_area = 0.1;        // fraction of the surface area, in [0, 1]
  double keep_frame_tolerance = 0.02;  // relative energy
  Progress* progress = nullptr;  // info line with the energies (nullptr = silent)
};

//! Result of orient_mesh().
struct OrientResult {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // proper rotation; canonical = rotation * input
  double energy_before = 0;  // E(identity)
  double energy_after = 0;   // E(rotation) <= energy_before
};

//! E(R) above for the mesh's faces (zero-area faces contribute nothing).
//! \throw InvalidMeshError if the total area is zero.
double orientation_energy(const Mesh& mesh, const Eigen::Matrix3d& rotation);

//! Finds the rotation minimising E (thesis Section 4.3.1, all three degrees of
//! freedom). Deterministic and independent of the thread count. Returns
//! exactly the identity when the best found is not better by more than
//! OrientOptions::min_relative_gain, or when the input is modelled in its
//! axes (OrientOptions::keep_frame_area).
//! \throw InvalidMeshError if the mesh has no faces or zero area;
//!        InvalidArgumentError if an option is out of range.
OrientResult orient_mesh(const Mesh& mesh, const OrientOptions& options = {});

}  // namespace subfab
