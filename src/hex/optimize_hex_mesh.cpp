// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/optimize_hex_mesh.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "hex/gauss_seidel_schedule.h"
#include "hex/hex_corners.h"
#include "hex/hex_optimizers.h"
#include "hex/hex_topology.h"
#include "hex/surface_projector.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/hex/scaled_jacobian.h"

namespace subfab {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

constexpr double kInvertedMargin = 0.02;  // the last-resort passes lift elements above this
constexpr double kProgress = 1e-3;        // improvement of the worst element that counts as progress
constexpr int kPatience = 10;             // passes without progress before giving up
constexpr double kArrived = 1e-12;        // squared distance at which a vertex is at its target
constexpr double kReach = 1.0;            // untangling moves a vertex at most this many mean edges

using detail::VertexStar;

struct Optimizer {
  HexMesh& mesh;
  const detail::HexTopology& topo;
  const detail::SurfaceProjector& surface;
  std::vector<Vec3> target;      // per boundary vertex: where it goes on the surface
  std::vector<char> on_surface;  // per vertex: a boundary vertex that has reached the surface
  std::vector<Vec3> origin;      // per vertex: where it was when the optimisation began
  std::vector<double> reach;     // per vertex: how far untangling may take it (its mean edge then)
  detail::CornerCache cache;  // corner determinants and edge units, kept up to date by every move

  //! Untangling may not take a vertex farther than its reach from where it
  //! began (a boundary vertex: from its target): otherwise an inverted
  //! corner "improves" towards 0 as the vertex runs away to infinity.
  bool within_reach(std::size_t v, const Vec3& q) const {
    const Vec3& anchor = topo.on_boundary[v] ? target[v] : origin[v];
    return (q - anchor).norm() <= reach[v];
  }

  //! With the cached energies of the fixed corners only for untangling.
  //! Fills `st`, a thread_local star of the caller (reused memory).
  const VertexStar& star(VertexStar& st, std::size_t v, bool energy = false) const {
    detail::build_vertex_star(st, mesh, topo.vertex_hexes[v], v, energy ? kSharpness : 0.0, &cache);
    return st;
  }
  //! After v moved: its corners' new values into the cache.
  void store(const VertexStar& st) { detail::store_star(mesh, st, cache); }
  //! The worst scaled Jacobian of v's hexahedra, from the cache (== worst_at).
  double cached_worst(std::size_t v) const {
    double worst = 1;
    for (int h : topo.vertex_hexes[v])
      for (std::size_t c = 0; c < 8; ++c) worst = std::min(worst, cache.values[8 * idx(h) + c]);
    return worst;
  }
  //! The scaled Jacobian of every hexahedron, from the cache.
  std::vector<double> qualities() const { return detail::hex_qualities(cache); }

  //! The worst scaled Jacobian of v's hexahedra.
  double worst_at(const VertexStar& st) const {
    double worst = 1;
    detail::evaluate_star(mesh, st);
    for (std::size_t j = 0; j < st.hexes->size(); ++j) worst = std::min(worst, detail::star_hex_quality(st, j));
    return worst;
  }
  //! `measure(st)` with v moved to `p` (v put back after).
  template <class Measure>
  double with_vertex_at(const VertexStar& st, const Vec3& p, Measure&& measure) {
    const Vec3 old = mesh.vertices[st.v];
    mesh.vertices[st.v] = p;
    const double q = measure(st);
    mesh.vertices[st.v] = old;
    return q;
  }
  double worst_if(const VertexStar& st, const Vec3& p) {
    return with_vertex_at(st, p, [this](const VertexStar& s) { return worst_at(s); });
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

  //! Guarded projection: every boundary vertex not yet on the surface moves
  //! towards its target, the whole way, half or a quarter of it, whichever
  //! first keeps the worst scaled Jacobian of its hexahedra at least
  //! min(floor, its value before). Returns the number of vertices moved.
  std::size_t project_step(double floor) {
    std::vector<std::size_t> order;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      if (topo.on_boundary[v] && !on_surface[v]) order.push_back(v);
    std::vector<char> moved(mesh.vertices.size(), 0);
    detail::gauss_seidel_sweep(mesh, topo, order, [&](std::size_t v) {
      const Vec3 p = mesh.vertices[v];
      const Vec3 d = target[v] - p;
      thread_local VertexStar buffer;
      const VertexStar& st = star(buffer, v);
      if (d.squaredNorm() <= kArrived) {
        mesh.vertices[v] = target[v];
        on_surface[v] = 1;
        store(st);
        return;
      }
      const double guard = std::min(floor, cached_worst(v));
      for (double t : {1.0, 0.5, 0.25}) {
        const Vec3 q = t == 1.0 ? target[v] : Vec3(p + t * d);
        if (worst_if(st, q) >= guard) {
          mesh.vertices[v] = q;
          on_surface[v] = t == 1.0;
          moved[v] = 1;
          store(st);
          break;
        }
      }
    });
    return static_cast<std::size_t>(std::count(moved.begin(), moved.end(), 1));
  }

  //! Smart smoothing pass; returns the number of vertices moved. Boundary
  //! vertices still off the surface are left to project_step().
  std::size_t smart_smooth() {
    std::vector<std::size_t> order;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      if (!topo.on_boundary[v] || on_surface[v]) order.push_back(v);
    std::vector<char> moved(mesh.vertices.size(), 0);
    detail::gauss_seidel_sweep(mesh, topo, order, [&](std::size_t v) {
      thread_local VertexStar buffer;
      const VertexStar& st = star(buffer, v);
      const double before = cached_worst(v);
      const Vec3 target_point = mean_target(v);
      if (worst_if(st, target_point) >= std::min(before, kSmoothCap)) {  // no worse (ignoring changes near 1)
        mesh.vertices[v] = target_point;
        moved[v] = 1;
        store(st);
      }
    });
    return static_cast<std::size_t>(std::count(moved.begin(), moved.end(), 1));
  }

  //! Soft-min energy of the corners of v's hexahedra: sum of
  //! exp(-sharpness x corner scaled Jacobian); dominated by the worst corners
  //! but smooth, so a gradient step can trade one corner against another.
  double energy_at(const VertexStar& st) const {
    detail::evaluate_star(mesh, st);
    double e = 0;
    for (std::size_t j = 0; j < st.hexes->size(); ++j)
      for (std::size_t i = 0; i < 8; ++i) {
        const int c = st.slot[8 * j + i];
        e += c >= 0 ? std::exp(-kSharpness * st.values[idx(c)]) : st.fixed_exp[8 * j + i];
      }
    return e;
  }
  double energy_if(const VertexStar& st, const Vec3& p) {
    return with_vertex_at(st, p, [this](const VertexStar& s) { return energy_at(s); });
  }

  //! A few gradient steps (central differences, backtracking) on the soft-min
  //! energy around v; a boundary vertex on the surface moves in the surface's
  //! tangent plane and is put back on the surface, unless `free_boundary`.
  //! True if the energy went down.
  bool untangle_vertex(std::size_t v, bool free_boundary) {
    const bool constrained = topo.on_boundary[v] && on_surface[v] && !free_boundary;
    const double scale = edge_scale(v);
    if (!(scale > 0)) return false;
    const double h = 1e-4 * scale;
    thread_local VertexStar buffer;
    const VertexStar& st = star(buffer, v, true);
    const Vec3 start_position = mesh.vertices[v];
    const double start = energy_at(st);
    double current = start;
    for (int iter = 0; iter < 4; ++iter) {
      const Vec3 p = mesh.vertices[v];
      Vec3 grad;
      for (int k = 0; k < 3; ++k) {
        Vec3 d = Vec3::Zero();
        d[k] = h;
        grad[k] = (energy_if(st, p + d) - energy_if(st, p - d)) / (2 * h);
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
        // a boundary vertex set free stays within a quarter edge of the surface
        else if (topo.on_boundary[v] && (surface.closest_point(q) - q).norm() > 0.25 * scale) continue;
        if (!within_reach(v, q)) continue;
        const double e = energy_if(st, q);
        if (e < current) {
          mesh.vertices[v] = q;
          current = e;
          moved = true;
          break;
        }
      }
      if (!moved) break;
    }
    if (mesh.vertices[v] != start_position) store(st);
    const bool improved = current < start * (1 - 1e-9);
    if (improved && topo.on_boundary[v] && !constrained) {  // it left or slid off the surface
      on_surface[v] = 0;
      target[v] = surface.closest_point(mesh.vertices[v]);
    }
    return improved;
  }

  //! Pattern search that raises the worst scaled Jacobian of v's hexahedra
  //! directly (the soft-min energy can stall with one corner held at 0 by
  //! the others): steps along the axes and the 8 cube diagonals, sizes
  //! 0.2 to 0.0125 of the mean edge, the first that raises the worst wins.
  //! Free boundary: used by the last resort only.
  bool raise_worst(std::size_t v) {
    const double scale = edge_scale(v);
    if (!(scale > 0)) return false;
    thread_local VertexStar buffer;
    const VertexStar& st = star(buffer, v);
    double current = worst_at(st);
    const double start = current;
    for (double step = 0.2 * scale; step > 0.01 * scale; step *= 0.5) {
      bool moved = true;
      for (int round = 0; round < 4 && moved; ++round) {
        moved = false;
        for (int d = 0; d < 14; ++d) {
          Vec3 dir = Vec3::Zero();
          if (d < 6) dir[d / 2] = d % 2 ? -1.0 : 1.0;
          else dir = Vec3((d - 6) & 1 ? -1.0 : 1.0, (d - 6) & 2 ? -1.0 : 1.0, (d - 6) & 4 ? -1.0 : 1.0) / std::sqrt(3.0);
          const Vec3 q = mesh.vertices[v] + step * dir;
          // a boundary vertex stays within a quarter edge of the surface
          if (topo.on_boundary[v] && (surface.closest_point(q) - q).norm() > 0.25 * scale) continue;
          if (!within_reach(v, q)) continue;
          const double w = worst_if(st, q);
          if (w > current + 1e-6) {
            mesh.vertices[v] = q;
            current = w;
            moved = true;
          }
        }
      }
    }
    if (current > start) store(st);
    if (current > start && topo.on_boundary[v]) {
      on_surface[v] = 0;
      target[v] = surface.closest_point(mesh.vertices[v]);
    }
    return current > start;
  }

  //! Sum of the distances of the boundary vertices still off the surface.
  double remaining() const {
    double s = 0;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      if (topo.on_boundary[v] && !on_surface[v]) s += (target[v] - mesh.vertices[v]).norm();
    return s;
  }

  static constexpr double kSharpness = 10.0;
  static constexpr double kSmoothCap = 0.999;
};


//! Passes of projection, smoothing and untangling until every element is
//! over `threshold` and every boundary vertex on the surface, or no progress
//! for kPatience passes, or `passes` passes. Untangling moves the vertices of
//! the elements under `threshold`; with `free_boundary` (the last resort)
//! their boundary vertices may leave the surface and nothing is projected.
int run_passes(Optimizer& opt, const OptimizeHexMeshOptions& options, double threshold, bool free_boundary,
               bool smooth) {
  HexMesh& mesh = opt.mesh;
  opt.cache = detail::corner_cache(mesh);
  double best = min_scaled_jacobian(opt.qualities());
  double best_remaining = free_boundary ? 0.0 : opt.remaining();
  int since_progress = 0, pass = 0;
  while (pass < options.passes) {
    ++pass;
    if (!free_boundary) opt.project_step(options.projection_floor);
    if (smooth) opt.smart_smooth();
    const auto sj = opt.qualities();
    std::vector<char> bad(mesh.vertices.size(), 0);
    for (std::size_t h = 0; h < sj.size(); ++h)
      if (sj[h] < threshold)
        for (int v : mesh.hexes[h]) bad[idx(v)] = 1;
    std::vector<std::size_t> order;
    for (std::size_t v = 0; v < bad.size(); ++v)
      if (bad[v]) order.push_back(v);
    detail::gauss_seidel_sweep(mesh, opt.topo, order, [&](std::size_t v) {
      opt.untangle_vertex(v, free_boundary);
      if (free_boundary) opt.raise_worst(v);
    });
    if (options.progress && !free_boundary)
      options.progress->update(static_cast<std::size_t>(pass), static_cast<std::size_t>(options.passes));
    // stop when done, or when neither the worst element nor the distance
    // left to the surface has improved for kPatience passes
    const double worst_now = min_scaled_jacobian(opt.qualities());
    const double left = free_boundary ? 0.0 : opt.remaining();
    if (worst_now >= threshold && left == 0) break;
    if (worst_now > best + kProgress || left < (1 - 1e-2) * best_remaining) {
      best = std::max(best, worst_now);
      best_remaining = std::min(best_remaining, left);
      since_progress = 0;
    } else if (++since_progress >= kPatience && !free_boundary) {
      break;
    }
  }
  return pass;
}

}  // namespace

OptimizeHexMeshReport optimize_hex_mesh(HexMesh& mesh, const Mesh& surface, const OptimizeHexMeshOptions& options) {
  const detail::SurfaceProjector projector(surface);
  return detail::optimize_hex_mesh(mesh, projector, options);
}

OptimizeHexMeshReport detail::optimize_hex_mesh(HexMesh& mesh, const SurfaceProjector& projector,
                                                const OptimizeHexMeshOptions& options) {
  OptimizeHexMeshReport report;
  const detail::HexTopology topo = detail::hex_topology(mesh);
  Optimizer opt{mesh, topo, projector, {}, {}, {}, {}, {}};
  opt.target.assign(mesh.vertices.size(), Vec3::Zero());
  opt.on_surface.assign(mesh.vertices.size(), 0);
  opt.origin = mesh.vertices;
  opt.reach.resize(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) opt.reach[v] = kReach * opt.edge_scale(v);
  {
    StageScope stage(options.progress, "project");
    if (options.targets && options.targets->size() != mesh.vertices.size())
      throw InvalidArgumentError("optimize_hex_mesh: " + std::to_string(options.targets->size()) +
                                 " targets for " + std::to_string(mesh.vertices.size()) + " vertices");
    parallel_for(0, mesh.vertices.size(), [&](std::size_t v) {
      if (topo.on_boundary[v])
        opt.target[v] = options.targets ? (*options.targets)[v] : projector.closest_point(mesh.vertices[v]);
    }, 512);
    report.min_before = min_scaled_jacobian(scaled_jacobians(mesh));
    opt.cache = detail::corner_cache(mesh);
    if (options.guard_projection) {
      opt.project_step(options.projection_floor);
    } else {  // unguarded: every boundary vertex straight to its target
      for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        if (topo.on_boundary[v]) mesh.vertices[v] = opt.target[v], opt.on_surface[v] = 1;
    }
    opt.relax(options.relax_iterations);
  }
  StageScope stage(options.progress, "optimise");
  report.passes = run_passes(opt, options, options.target_quality, false, options.smooth);
  // last resort for elements still inverted: their boundary vertices may
  // leave the surface (validity first; the distance report shows the cost)
  // (kept only if it raised the worst element: it can also push a tangle
  // further apart)
  if (const double before = min_scaled_jacobian(scaled_jacobians(mesh)); before <= kInvertedMargin) {
    const std::vector<Vec3> kept = mesh.vertices;
    const std::vector<char> kept_on_surface = opt.on_surface;
    run_passes(opt, options, kInvertedMargin, true, false);
    if (min_scaled_jacobian(scaled_jacobians(mesh)) <= before) mesh.vertices = kept, opt.on_surface = kept_on_surface;
  }
  const auto sj = scaled_jacobians(mesh);
  report.min_after = min_scaled_jacobian(sj);
  report.num_inverted = static_cast<std::size_t>(std::count_if(sj.begin(), sj.end(), [](double q) { return q <= 0; }));
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (topo.on_boundary[v] && !opt.on_surface[v]) ++report.num_off_surface;
  return report;
}

}  // namespace subfab
