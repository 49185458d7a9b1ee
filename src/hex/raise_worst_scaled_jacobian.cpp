// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/raise_worst_scaled_jacobian.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "hex/hex_optimizers.h"
#include "hex/hex_topology.h"
#include "hex/surface_projector.h"
#include "hex/worst_raiser.h"
#include "subfab/hex/scaled_jacobian.h"

namespace subfab {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

//! The patches of a round, worst first: the worst target hexahedron not yet
//! covered, its vertices grown by `rings` rings of edge neighbours (never
//! into an earlier patch); targets with a vertex in an earlier patch wait
//! for the next round. At most `max_patches`; each sorted.
std::vector<std::vector<std::size_t>> patches(const HexMesh& mesh, const detail::HexTopology& topo,
                                              const std::vector<double>& sj, double threshold, int rings,
                                              std::size_t max_patches) {
  std::vector<std::pair<double, std::size_t>> targets;
  for (std::size_t h = 0; h < sj.size(); ++h)
    if (sj[h] < threshold) targets.emplace_back(sj[h], h);
  std::sort(targets.begin(), targets.end());
  std::vector<char> taken(mesh.vertices.size(), 0);
  std::vector<std::vector<std::size_t>> out;
  for (const auto& [q, h] : targets) {
    if (out.size() >= max_patches) break;
    bool free = true;
    for (int v : mesh.hexes[h]) free = free && !taken[idx(v)];
    if (!free) continue;
    std::vector<std::size_t> patch;
    for (int v : mesh.hexes[h]) patch.push_back(idx(v)), taken[idx(v)] = 1;
    detail::grow_by_rings(patch, topo, rings, [&](std::size_t w) {
      if (taken[w]) return false;
      taken[w] = 1;
      return true;
    });
    std::sort(patch.begin(), patch.end());
    out.push_back(std::move(patch));
  }
  return out;
}

std::size_t count_below(const std::vector<double>& sj, double threshold) {
  return static_cast<std::size_t>(std::count_if(sj.begin(), sj.end(), [&](double q) { return q < threshold; }));
}

}  // namespace

RaiseWorstScaledJacobianReport detail::raise_worst_scaled_jacobian(HexMesh& mesh, const SurfaceProjector& projector,
                                                                   const RaiseWorstScaledJacobianOptions& options) {
  RaiseWorstScaledJacobianReport report;
  std::vector<double> sj = scaled_jacobians(mesh);
  report.min_before = report.min_after = min_scaled_jacobian(sj);
  report.avg_before = report.avg_after = mean_scaled_jacobian(sj);
  report.targets_before = report.targets_after = count_below(sj, options.threshold);
  if (report.targets_before == 0) return report;
  detail::WorstRaiser raiser(mesh, projector, options);
  if (options.max_off_surface > 0)
    for (std::size_t h = 0; h < sj.size(); ++h)
      if (sj[h] < options.threshold)
        for (int v : mesh.hexes[h]) raiser.loosen(idx(v), options.max_off_surface);
  while (report.rounds < options.rounds) {
    ++report.rounds;
    const double before = min_scaled_jacobian(sj);
    for (const auto& patch : patches(mesh, raiser.topology(), sj, options.threshold, options.rings, options.max_patches)) {
      raiser.raise(patch, report.steps);
      ++report.patches;
    }
    sj = scaled_jacobians(mesh);
    if (!(min_scaled_jacobian(sj) > before)) break;  // the worst element did not rise: another round would not lift it
  }
  report.min_after = min_scaled_jacobian(sj);
  report.avg_after = mean_scaled_jacobian(sj);
  report.targets_after = count_below(sj, options.threshold);
  return report;
}

RaiseWorstScaledJacobianReport raise_worst_scaled_jacobian(HexMesh& mesh, const Mesh& surface,
                                                           const RaiseWorstScaledJacobianOptions& options) {
  const detail::SurfaceProjector projector(surface);
  return detail::raise_worst_scaled_jacobian(mesh, projector, options);
}

}  // namespace subfab
