// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/pull_boundary_to_surface.h"

#include <algorithm>
#include <limits>

#include "hex/hex_optimizers.h"
#include "hex/hex_topology.h"
#include "hex/surface_projector.h"
#include "subfab/hex/scaled_jacobian.h"

namespace subfab {
namespace detail {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

double worst_of(const HexMesh& mesh, const std::vector<int>& hexes) {
  double q = std::numeric_limits<double>::infinity();
  for (int h : hexes) q = std::min(q, scaled_jacobian(mesh, idx(h)));
  return q;
}

}  // namespace

PullBoundaryReport pull_boundary_to_surface(HexMesh& mesh, const SurfaceProjector& surface,
                                            const PullBoundaryOptions& options) {
  PullBoundaryReport r;
  const HexTopology topo = hex_topology(mesh);
  const std::size_t n = mesh.vertices.size();
  std::vector<double> tol(n, 0.0);
  for (std::size_t v = 0; v < n; ++v) {
    if (!topo.on_boundary[v] || topo.neighbors[v].empty()) continue;
    double sum = 0;
    for (int w : topo.neighbors[v]) sum += (mesh.vertices[idx(w)] - mesh.vertices[v]).norm();
    tol[v] = options.tolerance * sum / static_cast<double>(topo.neighbors[v].size());
  }
  const auto count_off = [&](std::size_t& off, double& worst) {
    off = 0, worst = 0;
    for (std::size_t v = 0; v < n; ++v) {
      if (!topo.on_boundary[v]) continue;
      const double d = (surface.closest_point(mesh.vertices[v]) - mesh.vertices[v]).norm();
      worst = std::max(worst, d);
      off += d > tol[v];
    }
  };
  count_off(r.off_before, r.max_off_before);
  if (r.off_before == 0) return r;
  double floor = std::numeric_limits<double>::infinity();
  for (std::size_t h = 0; h < mesh.hexes.size(); ++h) floor = std::min(floor, scaled_jacobian(mesh, h));
  for (int sweep = 0; sweep < options.sweeps; ++sweep) {
    std::size_t moved = 0;
    for (std::size_t v = 0; v < n; ++v) {
      if (!topo.on_boundary[v]) continue;
      const Vec3 start = mesh.vertices[v];
      const Vec3 target = surface.closest_point(start);
      if (!((target - start).norm() > tol[v])) continue;
      const std::vector<int>& hexes = topo.vertex_hexes[v];
      const double before = worst_of(mesh, hexes);
      const double need = std::min(before, std::max(before - options.max_loss, floor));
      for (const double t : {1.0, 0.5, 0.25}) {
        mesh.vertices[v] = start + t * (target - start);
        if (worst_of(mesh, hexes) >= need) {
          ++moved;
          break;
        }
        mesh.vertices[v] = start;
      }
    }
    r.moves += moved;
    ++r.sweeps;
    if (moved == 0) break;
  }
  count_off(r.off_after, r.max_off_after);
  return r;
}

}  // namespace detail

PullBoundaryReport pull_boundary_to_surface(HexMesh& mesh, const Mesh& surface, const PullBoundaryOptions& options) {
  const detail::SurfaceProjector projector(surface);
  return detail::pull_boundary_to_surface(mesh, projector, options);
}

}  // namespace subfab
