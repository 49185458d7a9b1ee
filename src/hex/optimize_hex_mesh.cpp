// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/optimize_hex_mesh.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "hex/hex_topology.h"
#include "hex/surface_projector.h"
#include "subfab/core/parallel.h"
#include "subfab/hex/scaled_jacobian.h"

namespace subfab {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

struct Optimizer {
  HexMesh& mesh;
  const detail::HexTopology& topo;
  const detail::SurfaceProjector& surface;

  double worst_at(std::size_t v) const {
    double worst = 1;
    for (int h : topo.vertex_hexes[v]) worst = std::min(worst, scaled_jacobian(mesh, idx(h)));
    return worst;
  }
  double worst_if(std::size_t v, const Vec3& p) {
    const Vec3 old = mesh.vertices[v];
    mesh.vertices[v] = p;
    const double q = worst_at(v);
    mesh.vertices[v] = old;
    return q;
  }
  Vec3 mean_target(std::size_t v) const {
    const auto& nb = topo.on_boundary[v] ? topo.boundary_neighbors[v] : topo.neighbors[v];
    Vec3 c = Vec3::Zero();
    for (int w : nb) c += mesh.vertices[idx(w)];
    c /= static_cast<double>(nb.size());
    return topo.on_boundary[v] ? surface.closest_point(c) : c;
  }
  double edge_scale(std::size_t v) const {
    double s = 0;
    for (int w : topo.neighbors[v]) s += (mesh.vertices[idx(w)] - mesh.vertices[v]).norm();
    return s / static_cast<double>(std::max<std::size_t>(1, topo.neighbors[v].size()));
  }

  void relax(int iterations) {
    for (int it = 0; it < iterations; ++it) {
      std::vector<Vec3> next(mesh.vertices.size());
      parallel_for(0, next.size(), [&](std::size_t v) { next[v] = mean_target(v); }, 512);
      mesh.vertices = std::move(next);
    }
  }

  //! Smart smoothing pass; returns the number of vertices moved.
  std::size_t smart_smooth() {
    std::size_t moved = 0;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
      const double before = worst_at(v);
      const Vec3 target = mean_target(v);
      if (worst_if(v, target) >= std::min(before, 0.999)) {  // no worse (ignore the last fraction near 1)
        mesh.vertices[v] = target;
        ++moved;
      }
    }
    return moved;
  }

  //! Pattern search on the worst scaled Jacobian around v; true if improved.
  bool untangle_vertex(std::size_t v) {
    double best = worst_at(v);
    const double start = best;
    double step = 0.25 * edge_scale(v);
    Vec3 normal = Vec3::UnitZ();
    if (topo.on_boundary[v]) surface.closest_point(mesh.vertices[v], &normal);
    for (int iter = 0; iter < 12 && step > 0; ++iter) {
      Vec3 dirs[6] = {Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()};
      int num_dirs = 6;
      if (topo.on_boundary[v]) {
        const Vec3 a = (std::abs(normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(normal).normalized();
        const Vec3 b = normal.cross(a);
        dirs[0] = a, dirs[1] = -a, dirs[2] = b, dirs[3] = -b;
        num_dirs = 4;
      }
      bool improved = false;
      for (int d = 0; d < num_dirs; ++d) {
        Vec3 p = mesh.vertices[v] + step * dirs[d];
        if (topo.on_boundary[v]) p = surface.closest_point(p);
        const double q = worst_if(v, p);
        if (q > best + 1e-9) {
          best = q;
          mesh.vertices[v] = p;
          improved = true;
        }
      }
      if (!improved) step *= 0.5;
    }
    return best > start + 1e-9;
  }
};

}  // namespace

OptimizeHexMeshReport optimize_hex_mesh(HexMesh& mesh, const Mesh& surface, const OptimizeHexMeshOptions& options) {
  OptimizeHexMeshReport report;
  const detail::HexTopology topo = detail::hex_topology(mesh);
  const detail::SurfaceProjector projector(surface);
  Optimizer opt{mesh, topo, projector};
  {
    StageScope stage(options.progress, "relax");
    // boundary vertices onto the surface first
    parallel_for(0, mesh.vertices.size(), [&](std::size_t v) {
      if (topo.on_boundary[v]) mesh.vertices[v] = projector.closest_point(mesh.vertices[v]);
    }, 512);
    opt.relax(options.relax_iterations);
  }
  auto worst = [&] {
    const auto sj = scaled_jacobians(mesh);
    return sj.empty() ? 1.0 : *std::min_element(sj.begin(), sj.end());
  };
  report.min_before = worst();
  StageScope stage(options.progress, "optimise");
  for (int pass = 0; pass < options.passes; ++pass) {
    report.passes = pass + 1;
    opt.smart_smooth();
    const auto sj = scaled_jacobians(mesh);
    std::vector<bool> bad(mesh.vertices.size(), false);
    for (std::size_t h = 0; h < sj.size(); ++h)
      if (sj[h] < options.target_quality)
        for (int v : mesh.hexes[h]) bad[idx(v)] = true;
    std::size_t improved = 0;
    for (std::size_t v = 0; v < bad.size(); ++v)
      if (bad[v]) improved += opt.untangle_vertex(v);
    if (options.progress) options.progress->update(static_cast<std::size_t>(pass + 1), static_cast<std::size_t>(options.passes));
    if (improved == 0) break;
  }
  const auto sj = scaled_jacobians(mesh);
  report.min_after = sj.empty() ? 1.0 : *std::min_element(sj.begin(), sj.end());
  report.num_inverted = static_cast<std::size_t>(std::count_if(sj.begin(), sj.end(), [](double q) { return q <= 0; }));
  return report;
}

}  // namespace subfab
