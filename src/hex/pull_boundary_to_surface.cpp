// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/pull_boundary_to_surface.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "hex/hex_optimizers.h"
#include "hex/hex_topology.h"
#include "hex/surface_projector.h"
#include "hex/worst_raiser.h"
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

//! The second stage (see the header): the vertices still off the surface, by
//! clusters (connected along boundary edges), are moved to their closest
//! points in `patch_stages` steps, the cluster's neighbourhood re-optimised
//! after each; the last step that keeps the patch's quality is kept.
void snap_held_vertices(HexMesh& mesh, const SurfaceProjector& surface, const HexTopology& topo,
                        const std::vector<double>& tol, double floor, const PullBoundaryOptions& options,
                        PullBoundaryReport& r) {
  const std::size_t n = mesh.vertices.size();
  std::vector<char> held(n, 0);
  const auto find_held = [&] {
    std::size_t count = 0;
    for (std::size_t v = 0; v < n; ++v)
      if (topo.on_boundary[v]) {
        held[v] = (surface.closest_point(mesh.vertices[v]) - mesh.vertices[v]).norm() > tol[v];
        count += held[v];
      }
    return count;
  };
  r.held = find_held();
  if (r.held == 0) return;
  RaiseWorstScaledJacobianOptions wo;
  wo.max_steps = options.patch_steps;
  wo.restarts = options.patch_restarts;
  wo.max_slide = options.patch_slide;
  WorstRaiser raiser(mesh, surface, wo);
  std::vector<int> mark(n, -1);  // per vertex: the first vertex of the last cluster whose patch took it
  std::vector<std::size_t> cluster, patch, moving;
  std::vector<int> hexes;
  std::vector<Vec3> start, target, saved, good;
  std::vector<WorstRaiser::Pinned> pinned;
  std::vector<std::pair<std::size_t, Vec3>> carried;  // inner neighbours of the cluster and their step per stage
  for (int sweep = 0; sweep < options.snap_sweeps; ++sweep) {
    if (sweep > 0 && find_held() == 0) break;
    std::size_t progress = 0;
    for (std::size_t seed = 0; seed < n; ++seed) {
      if (!held[seed]) continue;
      const int tag = static_cast<int>(seed);
      // the cluster: held vertices connected to the seed along boundary edges (breadth first, at most max_cluster)
      cluster.assign(1, seed);
      held[seed] = 0;
      for (std::size_t i = 0; i < cluster.size() && cluster.size() < options.max_cluster; ++i)
        for (int w : topo.boundary_neighbors[cluster[i]])
          if (held[idx(w)] && cluster.size() < options.max_cluster) cluster.push_back(idx(w)), held[idx(w)] = 0;
      std::sort(cluster.begin(), cluster.end());
      // the patch: the cluster and `rings` rings of edge neighbours
      patch = cluster;
      for (std::size_t v : patch) mark[v] = tag;
      grow_by_rings(patch, topo, options.rings, [&](std::size_t w) {
        if (mark[w] == tag) return false;
        mark[w] = tag;
        return true;
      });
      std::sort(patch.begin(), patch.end());
      moving.clear();
      for (std::size_t v : patch)
        if (!std::binary_search(cluster.begin(), cluster.end(), v)) moving.push_back(v);
      hexes.clear();
      for (std::size_t w : patch) hexes.insert(hexes.end(), topo.vertex_hexes[w].begin(), topo.vertex_hexes[w].end());
      std::sort(hexes.begin(), hexes.end());
      hexes.erase(std::unique(hexes.begin(), hexes.end()), hexes.end());
      const double before = worst_of(mesh, hexes);
      const double need = std::min(before, std::max(floor, options.patch_floor));
      start.resize(cluster.size());
      target.resize(cluster.size());
      for (std::size_t i = 0; i < cluster.size(); ++i)
        start[i] = mesh.vertices[cluster[i]], target[i] = surface.closest_point(start[i]);
      saved.resize(patch.size());
      for (std::size_t i = 0; i < patch.size(); ++i) saved[i] = mesh.vertices[patch[i]];
      good = saved;
      pinned.clear();
      for (std::size_t i = 0; i < cluster.size(); ++i) pinned.push_back(raiser.pin(cluster[i], start[i]));
      // the cluster moves by 1/stages of the way at a time, fixed while the
      // rest of the patch follows; at the surface it slides with the patch
      int reached = 0;
      std::size_t steps = 0;
      // the inner neighbours of the cluster (the other ends of its padding
      // edges) are carried along by the mean step of their cluster neighbours:
      // the padding edge keeps its direction (a corner cannot turn inside out
      // by a gradient step of the normalised corners, so it must not start so)
      carried.clear();
      for (std::size_t i = 0; i < cluster.size(); ++i)
        for (int w : topo.neighbors[cluster[i]])
          if (!topo.on_boundary[idx(w)]) carried.emplace_back(idx(w), (target[i] - start[i]) / options.patch_stages);
      std::sort(carried.begin(), carried.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      std::size_t distinct = 0;  // one mean step per inner neighbour
      for (std::size_t i = 0; i < carried.size();) {
        const std::size_t w = carried[i].first;
        Vec3 sum = Vec3::Zero();
        int count = 0;
        for (; i < carried.size() && carried[i].first == w; ++i) sum += carried[i].second, ++count;
        carried[distinct++] = {w, sum / count};
      }
      carried.resize(distinct);
      for (int k = 1; k <= options.patch_stages; ++k) {
        const double t = static_cast<double>(k) / options.patch_stages;
        for (const auto& [w, step] : carried) mesh.vertices[w] += step;
        for (std::size_t i = 0; i < cluster.size(); ++i)
          raiser.pin(cluster[i], k == options.patch_stages ? target[i] : Vec3(start[i] + t * (target[i] - start[i])));
        if (worst_of(mesh, hexes) < need) raiser.raise(k == options.patch_stages ? patch : moving, steps);
        if (!(worst_of(mesh, hexes) >= need)) break;
        reached = k;
        for (std::size_t i = 0; i < patch.size(); ++i) good[i] = mesh.vertices[patch[i]];
      }
      // keep the last stage that held the quality (none: back to the start)
      for (std::size_t i = 0; i < patch.size(); ++i) mesh.vertices[patch[i]] = good[i];
      for (std::size_t i = 0; i < cluster.size(); ++i) {
        const Vec3 kept = mesh.vertices[cluster[i]];
        raiser.unpin(pinned[i]);  // its origin and allowance as before
        if (reached > 0) raiser.pin(cluster[i], kept);
      }
      r.snap_steps += steps;
      if (reached == options.patch_stages) r.snapped += cluster.size();
      else if (reached > 0) r.closer += cluster.size();
      progress += reached > 0;
    }
    ++r.snap_sweeps;
    if (progress == 0) break;
  }
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
  if (options.rings > 0) snap_held_vertices(mesh, surface, topo, tol, floor, options, r);
  count_off(r.off_after, r.max_off_after);
  return r;
}

}  // namespace detail

PullBoundaryReport pull_boundary_to_surface(HexMesh& mesh, const Mesh& surface, const PullBoundaryOptions& options) {
  const detail::SurfaceProjector projector(surface);
  return detail::pull_boundary_to_surface(mesh, projector, options);
}

}  // namespace subfab
