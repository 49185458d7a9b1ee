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

constexpr double kInvertedMargin = 0.02;  // the last-resort pass lifts elements above this
constexpr double kProgress = 1e-3;        // improvement of the worst element that counts as progress
constexpr int kPatience = 10;             // passes without progress before giving up

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
      if (worst_if(v, target) >= std::min(before, kSmoothCap)) {  // no worse (ignoring changes near 1)
        mesh.vertices[v] = target;
        ++moved;
      }
    }
    return moved;
  }

  //! Soft-min energy of the corners of v's hexahedra: sum of
  //! exp(-sharpness x corner scaled Jacobian); dominated by the worst corners
  //! but smooth, so a gradient step can trade one corner against another.
  double energy_at(std::size_t v) const {
    double e = 0;
    for (int h : topo.vertex_hexes[v]) {
      const Hex& hex = mesh.hexes[idx(h)];
      for (std::size_t i = 0; i < 8; ++i) {
        const auto& n = kHexCornerNeighbors[i];
        const Vec3& p = mesh.vertices[idx(hex[i])];
        Vec3 ed[3];
        double alpha = 0;
        bool degenerate = false;
        for (std::size_t k = 0; k < 3; ++k) {
          ed[k] = mesh.vertices[idx(hex[idx(n[k])])] - p;
          const double len = ed[k].norm();
          if (!(len > 0)) degenerate = true;
          else ed[k] /= len;
        }
        alpha = degenerate ? -1.0 : ed[0].dot(ed[1].cross(ed[2]));
        e += std::exp(-kSharpness * alpha);
      }
    }
    return e;
  }
  double energy_if(std::size_t v, const Vec3& p) {
    const Vec3 old = mesh.vertices[v];
    mesh.vertices[v] = p;
    const double e = energy_at(v);
    mesh.vertices[v] = old;
    return e;
  }

  //! A few gradient steps (central differences, backtracking) on the soft-min
  //! energy around v; a boundary vertex moves in the surface's tangent plane
  //! and is put back on the surface. True if the energy went down.
  bool untangle_vertex(std::size_t v, bool free_boundary = false) {
    const bool constrained = topo.on_boundary[v] && !free_boundary;
    const double scale = edge_scale(v);
    if (!(scale > 0)) return false;
    const double h = 1e-4 * scale;
    const double start = energy_at(v);
    double current = start;
    for (int iter = 0; iter < 4; ++iter) {
      const Vec3 p = mesh.vertices[v];
      Vec3 grad;
      for (int k = 0; k < 3; ++k) {
        Vec3 d = Vec3::Zero();
        d[k] = h;
        grad[k] = (energy_if(v, p + d) - energy_if(v, p - d)) / (2 * h);
      }
      if (constrained) {
        Vec3 normal;
        surface.closest_point(p, &normal);
        grad -= grad.dot(normal) * normal;
      }
      const double g = grad.norm();
      if (!(g > 0)) break;
      const Vec3 dir = -grad / g;
      double step = 0.2 * scale;
      bool moved = false;
      for (int ls = 0; ls < 10; ++ls, step *= 0.5) {
        Vec3 q = p + step * dir;
        if (constrained) q = surface.closest_point(q);
        const double e = energy_if(v, q);
        if (e < current) {
          mesh.vertices[v] = q;
          current = e;
          moved = true;
          break;
        }
      }
      if (!moved) break;
    }
    return current < start * (1 - 1e-9);
  }

  static constexpr double kSharpness = 10.0;
  static constexpr double kSmoothCap = 0.999;
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
  double best = report.min_before;
  int since_progress = 0;
  for (int pass = 0; pass < options.passes; ++pass) {
    report.passes = pass + 1;
    if (options.smooth) opt.smart_smooth();
    const auto sj = scaled_jacobians(mesh);
    std::vector<bool> bad(mesh.vertices.size(), false);
    for (std::size_t h = 0; h < sj.size(); ++h)
      if (sj[h] < options.target_quality)
        for (int v : mesh.hexes[h]) bad[idx(v)] = true;
    for (std::size_t v = 0; v < bad.size(); ++v)
      if (bad[v]) opt.untangle_vertex(v);
    if (options.progress) options.progress->update(static_cast<std::size_t>(pass + 1), static_cast<std::size_t>(options.passes));
    // stop when every element is good enough, or when the worst one has
    // not improved by kProgress for kPatience passes
    const auto after = scaled_jacobians(mesh);
    const double worst_now = after.empty() ? 1.0 : *std::min_element(after.begin(), after.end());
    if (worst_now >= options.target_quality) break;
    if (worst_now > best + kProgress) {
      best = worst_now;
      since_progress = 0;
    } else if (++since_progress >= kPatience) {
      break;
    }
  }
  // last resort for elements still inverted: their boundary vertices may
  // leave the surface (validity first; the distance report shows the cost)
  for (int pass = 0; pass < options.passes; ++pass) {
    const auto sj = scaled_jacobians(mesh);
    std::vector<bool> bad(mesh.vertices.size(), false);
    bool any = false;
    for (std::size_t h = 0; h < sj.size(); ++h)
      if (sj[h] <= kInvertedMargin) {
        any = true;
        for (int v : mesh.hexes[h]) bad[idx(v)] = true;
      }
    if (!any) break;
    for (std::size_t v = 0; v < bad.size(); ++v)
      if (bad[v]) opt.untangle_vertex(v, true);
  }
  const auto sj = scaled_jacobians(mesh);
  report.min_after = sj.empty() ? 1.0 : *std::min_element(sj.begin(), sj.end());
  report.num_inverted = static_cast<std::size_t>(std::count_if(sj.begin(), sj.end(), [](double q) { return q <= 0; }));
  return report;
}

}  // namespace subfab
