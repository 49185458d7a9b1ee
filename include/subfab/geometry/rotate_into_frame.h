// SPDX-License-Identifier: GPL-3.0-or-later
//! \file rotate_into_frame.h
//! A mesh in the working frame of the decomposition (thesis Section 4.3.1:
//! the input turned so that its faces align with the axes), exactly as
//! decompose() makes it: `subfab validate` turns the input the same way to
//! measure a decomposition within a tolerance where decompose measured it
//! (check 10, issue 17; docs/validate.md).
#pragma once

#include <Eigen/Core>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! The snapping decompose() uses (OrientOptions::snap_tolerance's default):
//! fraction of the turned mesh's bounding-box diagonal.
inline constexpr double kFrameSnapTolerance = 1e-9;

//! The mesh in the frame `rotation` (canonical = rotation * input), as
//! decompose() and orient_mesh() use it: unchanged (bit for bit) for the
//! identity; otherwise turned, then along each axis coordinates that differ by
//! at most snap_tolerance x bbox diagonal (chains of them) are set to the
//! group's median value, unless that would make a face degenerate (then the
//! turned mesh is returned as is). Vertex and face ids are kept.
//! Deterministic (plain IEEE operations): the same bits for the same input.
Mesh rotate_into_frame(const Mesh& mesh, const Eigen::Matrix3d& rotation, double snap_tolerance);

//! rotate_into_frame()'s snapping alone, in the mesh's own frame: along each
//! axis, coordinates that differ by at most snap_tolerance x bbox diagonal
//! (chains of them) set to the group's median, unless that makes a face
//! degenerate (then `mesh` is returned as is). Vertex and face ids are kept.
Mesh snap_coordinates(const Mesh& mesh, double snap_tolerance);

}  // namespace subfab
