// SPDX-License-Identifier: GPL-3.0-or-later
//! \file require_closed_solid.h
//! The gate every solid-based command (decompose, unfold, ...) passes its
//! input through before doing any work.
#pragma once

#include <string>

#include "subfab/core/progress.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Checks that `mesh` is a closed, manifold, consistently oriented,
//! non-degenerate, self-intersection-free solid. An inward-oriented mesh
//! (negative volume) is flipped in place with a warning through `progress`.
//! Several components are allowed (reported through `progress`).
//! \throw InvalidMeshError naming the first failing check, with counts,
//!        example ids and what the user can do.
void require_closed_solid(Mesh& mesh, Progress* progress = nullptr);

//! The same gate for a mesh an algorithm made (its own result), on a copy:
//! `mesh` is not changed, and a mesh oriented inward as a whole passes.
//! \throw AlgorithmError `before` + the message of require_closed_solid()'s
//!        InvalidMeshError + `after`.
void require_closed_solid_result(const Mesh& mesh, const std::string& before,
                                 const std::string& after = "");

}  // namespace subfab
