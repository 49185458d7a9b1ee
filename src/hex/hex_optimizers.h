// SPDX-License-Identifier: GPL-3.0-or-later
//! \file hex_optimizers.h
//! Private: optimize_hex_mesh(), raise_min_scaled_jacobian(),
//! pull_boundary_to_surface(), raise_worst_scaled_jacobian() and raise_mean_scaled_jacobian() on a surface
//! whose projector (AABB tree and exact inside test) is already built, so
//! that hexmesh() builds it once instead of once per level.
#pragma once

#include "hex/surface_projector.h"
#include "subfab/hex/optimize_hex_mesh.h"
#include "subfab/hex/pull_boundary_to_surface.h"
#include "subfab/hex/raise_mean_scaled_jacobian.h"
#include "subfab/hex/raise_min_scaled_jacobian.h"
#include "subfab/hex/raise_worst_scaled_jacobian.h"

namespace subfab::detail {

OptimizeHexMeshReport optimize_hex_mesh(HexMesh& mesh, const SurfaceProjector& surface,
                                        const OptimizeHexMeshOptions& options);

RaiseMinScaledJacobianReport raise_min_scaled_jacobian(HexMesh& mesh, const SurfaceProjector& surface,
                                                       const RaiseMinScaledJacobianOptions& options);

PullBoundaryReport pull_boundary_to_surface(HexMesh& mesh, const SurfaceProjector& surface,
                                            const PullBoundaryOptions& options);
RaiseWorstScaledJacobianReport raise_worst_scaled_jacobian(HexMesh& mesh, const SurfaceProjector& surface,
                                                           const RaiseWorstScaledJacobianOptions& options);
RaiseMeanScaledJacobianReport raise_mean_scaled_jacobian(HexMesh& mesh, const SurfaceProjector& surface,
                                                         const RaiseMeanScaledJacobianOptions& options);

}  // namespace subfab::detail
