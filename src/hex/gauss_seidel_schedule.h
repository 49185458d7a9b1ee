// SPDX-License-Identifier: GPL-3.0-or-later
//! \file gauss_seidel_schedule.h
//! Private: parallel Gauss-Seidel sweeps of the optimisers of D.6
//! (optimize_hex_mesh, raise_min_scaled_jacobian) with exactly the result of
//! the serial sweep. A vertex visit reads the positions of the vertices of
//! the vertex's hexahedra and moves only that vertex, so two visits commute
//! when their vertices share no hexahedron. The schedule puts each vertex of
//! the sweep order in the first wave after every earlier vertex it shares a
//! hexahedron with (a wavefront, the classic parallel Gauss-Seidel ordering);
//! the vertices of one wave run in parallel. Every visit then sees the very
//! positions the serial sweep would show it: same result, bit for bit,
//! whatever the number of threads.
#pragma once

#include <cstddef>
#include <vector>

#include "hex/hex_topology.h"
#include "subfab/core/parallel.h"
#include "subfab/hex/hex_mesh.h"

namespace subfab::detail {

//! The waves of a sweep over `order` (vertex indices, each at most once):
//! the vertices of each wave in their order in `order`.
std::vector<std::vector<std::size_t>> gauss_seidel_schedule(const HexMesh& mesh, const HexTopology& topo,
                                                            const std::vector<std::size_t>& order);

//! Calls visit(v) for every vertex of `waves`, wave after wave, the vertices
//! of one wave in parallel. visit(v) may move v and read the vertices of v's
//! hexahedra; it must change nothing else shared (per-vertex slots only).
template <class Visit>
void run_waves(const std::vector<std::vector<std::size_t>>& waves, Visit&& visit) {
  for (const std::vector<std::size_t>& wave : waves) {
    if (wave.size() < 3) {
      for (std::size_t v : wave) visit(v);
    } else {
      parallel_for(0, wave.size(), [&](std::size_t i) { visit(wave[i]); }, 2);
    }
  }
}

//! Both: the serial sweep over `order`, in parallel.
template <class Visit>
void gauss_seidel_sweep(const HexMesh& mesh, const HexTopology& topo, const std::vector<std::size_t>& order,
                        Visit&& visit) {
  run_waves(gauss_seidel_schedule(mesh, topo, order), visit);
}

}  // namespace subfab::detail
