// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/raise_min_scaled_jacobian.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "hex/gauss_seidel_schedule.h"
#include "hex/hex_corners.h"
#include "hex/hex_optimizers.h"
#include "hex/hex_topology.h"
#include "hex/surface_projector.h"
#include "subfab/hex/scaled_jacobian.h"

namespace subfab {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

constexpr double kSharpness = 8.0;      // energy of a vertex: sum over its hexahedra of exp(-kSharpness (q - q_min)) ...
constexpr double kLinear = 1.0;         // ... minus kLinear x q: the average counts too
constexpr double kGain = 1e-9;          // the pattern search must raise the smallest corner by this much
constexpr double kPatternBelow = 0.15;  // the pattern search (pure max-min, which can sacrifice good corners) runs under this
constexpr int kMovesPerVisit = 8;       // line searches per vertex visit
constexpr double kSweepGain = 1e-4;     // a sweep that raises the minimum and the deficit less than this ends the passes
constexpr double kMargin = 0.02;        // the last resort lifts the elements under this
constexpr double kUntangle = 10.0;       // joint untangling: energy sum exp(-kUntangle x corner)
constexpr int kUntangleSteps = 500;     // joint untangling: at most this many steps
//! The repairs the last resort tries in turn, each from the same start,
//! until one lifts every element over kMargin (else the best is kept): the
//! patch grown by `rings`, its inside reset by `laplacian` iterations first.
struct Repair {
  int rings;
  int laplacian;
};
constexpr Repair kRepairs[] = {{1, 0}, {2, 30}, {3, 100}};
constexpr double kMaxStep = 0.2;        // joint untangling: largest step of a vertex, fraction of its mean edge

using detail::HexCorner;

class Raiser {
 public:
  Raiser(HexMesh& mesh, const detail::SurfaceProjector& surface)
      : mesh_(mesh), surface_(surface), topo_(detail::hex_topology(mesh)), corners_(detail::vertex_corners(mesh)) {
    scale_.resize(mesh.vertices.size());
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) scale_[v] = edge_scale(v);
  }

  const detail::HexTopology& topology() const { return topo_; }
  //! The corner cache the sweeps' visits read and update: refreshed at the
  //! start of a sweep (the joint untangling moves vertices without it).
  void refresh_corners() { cache_ = detail::corner_cache(mesh_); }
  std::vector<double> qualities() const { return detail::hex_qualities(cache_); }

  double corner_value(const HexCorner& k) const { return detail::corner_determinant(mesh_, k); }

  //! Smallest corner v affects, with v at p.
  double local_min(const detail::VertexStar& st, const Vec3& p) {
    const Vec3 old = mesh_.vertices[st.v];
    mesh_.vertices[st.v] = p;
    detail::evaluate_star(mesh_, st);
    const double m = detail::star_min_moved(st);
    mesh_.vertices[st.v] = old;
    return m;
  }
  double soft_energy(const detail::VertexStar& st, const Vec3& p, double shift) {
    const Vec3 old = mesh_.vertices[st.v];
    mesh_.vertices[st.v] = p;
    detail::evaluate_star(mesh_, st);
    double e = 0;
    for (std::size_t j = 0; j < st.hexes->size(); ++j) {
      const double q = detail::star_hex_quality(st, j);
      e += std::exp(-kSharpness * (q - shift)) - kLinear * q;
    }
    if (attraction_ > 0 && loose_[st.v]) {  // a loose boundary vertex is drawn back to the surface
      const double d = distance_to_surface(p) / scale_[st.v];
      e += attraction_ * d * d;
    }
    mesh_.vertices[st.v] = old;
    return e;
  }

  double distance_to_surface(const Vec3& p) const { return (surface_.closest_point(p) - p).norm(); }

  //! Where a step from v's position to q really goes (a boundary vertex on
  //! the surface is put back onto it), and whether it is allowed there.
  bool place(std::size_t v, const Vec3& q, bool free_boundary, Vec3& out) const {
    if (!topo_.on_boundary[v]) {
      out = q;
      return true;
    }
    const Vec3 onto = surface_.closest_point(q);
    if (!free_boundary) {
      out = onto;
      return true;
    }
    const double d = (onto - q).norm();
    if (d > allowance_[v]) return false;
    out = q;
    return true;
  }

  //! Visits v: line searches along the descent direction of the soft-min
  //! of its affected corners (a step must lower the soft-min energy and keep
  //! the smallest corner), then, when that stalls, a pattern search that
  //! raises the smallest corner. Returns the number of accepted moves. A
  //! loose vertex (set_loose) is free within its allowance whatever
  //! `free_boundary_all` says.
  std::size_t visit(std::size_t v, bool free_boundary_all) {
    const bool free_boundary = free_boundary_all || (attraction_ > 0 && loose_[v]);
    const double scale = scale_[v];
    if (!(scale > 0)) return 0;
    std::size_t moves = 0;
    thread_local detail::VertexStar st;  // reused memory
    detail::build_vertex_star(st, mesh_, topo_.vertex_hexes[v], v, 0.0, &cache_);
    Score current = score(st, mesh_.vertices[v], local_min(st, mesh_.vertices[v]));
    const bool slides = topo_.on_boundary[v] && !free_boundary;
    for (int it = 0; it < kMovesPerVisit; ++it) {
      const Vec3 p = mesh_.vertices[v];
      const double shift = current.min;
      current = score(st, p, shift);
      const double h = 1e-5 * scale;
      Vec3 grad;
      for (int a = 0; a < 3; ++a) {
        Vec3 d = Vec3::Zero();
        d[a] = h;
        grad[a] = (soft_energy(st, p + d, shift) - soft_energy(st, p - d, shift)) / (2 * h);
      }
      if (slides) {
        Vec3 normal;
        surface_.closest_point(p, &normal);
        grad -= grad.dot(normal) * normal;
      }
      bool moved = false;
      if (const double g = grad.norm(); g > 0) moved = line_search(st, -grad / g, scale, free_boundary, shift, current);
      if (!moved && current.min < kPatternBelow) moved = pattern_search(st, scale, free_boundary, shift, current);
      if (!moved) break;
      ++moves;
    }
    if (moves > 0) detail::store_star(mesh_, st, cache_);
    return moves;
  }

  //! Joint untangling of a patch: every vertex of `patch` moves at once
  //! along the descent direction (analytic gradient) of sum exp(-kUntangle x
  //! corner) over the corners the patch affects (each vertex's step scaled by its squared mean
  //! edge, at most kMaxStep of it), backtracking on that sum; boundary vertices
  //! stay within their allowance of the surface. A coordinate-wise search
  //! stalls where two vertices must move together (a fold of the boundary at
  //! a thin rim); this does not. Returns the number of steps taken.
  static double untangle_energy(double alpha) { return std::exp(-kUntangle * alpha); }
  static double untangle_slope(double alpha) { return -kUntangle * std::exp(-kUntangle * alpha); }
  int untangle_patch(const std::vector<std::size_t>& patch, int iterations) {
    std::vector<char> in_patch(mesh_.vertices.size(), 0);
    for (std::size_t v : patch) in_patch[v] = 1;
    // the hexahedra whose corners move
    std::vector<int> hexes;
    for (std::size_t v : patch) hexes.insert(hexes.end(), topo_.vertex_hexes[v].begin(), topo_.vertex_hexes[v].end());
    std::sort(hexes.begin(), hexes.end());
    hexes.erase(std::unique(hexes.begin(), hexes.end()), hexes.end());
    auto total = [&] {
      double e = 0;
      for (int h : hexes)
        for (int c = 0; c < 8; ++c) e += untangle_energy(corner_value({h, c}));
      return e;
    };
    double energy = total();
    int steps = 0;
    std::vector<Vec3> dir(patch.size());
    for (int it = 0; it < iterations; ++it) {
      for (std::size_t i = 0; i < patch.size(); ++i) {
        const std::size_t v = patch[i];
        Vec3 g = Vec3::Zero(), dg;
        for (const HexCorner& k : corners_[v]) {
          const double alpha = detail::corner_determinant_gradient(mesh_, k, static_cast<int>(v), dg);
          g += untangle_slope(alpha) * dg;
        }
        dir[i] = -scale_[v] * scale_[v] * g;
        if (const double len = dir[i].norm(); len > kMaxStep * scale_[v]) dir[i] *= kMaxStep * scale_[v] / len;
      }
      const std::vector<Vec3> start = mesh_.vertices;
      bool moved = false;
      for (double t = 1.0; t > 1e-4; t *= 0.5) {
        for (std::size_t i = 0; i < patch.size(); ++i) {
          const std::size_t v = patch[i];
          Vec3 q = start[v] + t * dir[i];
          if (topo_.on_boundary[v]) {  // within its allowance of the surface
            const Vec3 c = surface_.closest_point(q);
            const double d = (q - c).norm();
            if (d > allowance_[v]) q = c + (allowance_[v] / d) * (q - c);
          }
          mesh_.vertices[v] = q;
        }
        const double e = total();
        if (e < energy * (1 - 1e-9)) {
          energy = e;
          moved = true;
          break;
        }
        for (std::size_t v : patch) mesh_.vertices[v] = start[v];
      }
      if (!moved) break;
      ++steps;
    }
    return steps;
  }

  //! Boundary vertex v is loose: in the sweeps that follow it moves freely
  //! within `allowance` of the surface, its energy plus
  //! attraction x (distance to the surface / its mean edge)^2.
  void set_loose(std::size_t v, double allowance, double attraction) {
    if (loose_.empty()) loose_.assign(mesh_.vertices.size(), 0);
    loose_[v] = 1;
    allowance_[v] = std::max(allowance_[v], allowance);
    attraction_ = attraction;
  }
  bool loose(std::size_t v) const { return !loose_.empty() && loose_[v]; }
  void set_allowance(std::size_t v, double a) { allowance_[v] = a; }
  double allowance(std::size_t v) const { return allowance_[v]; }
  void init_allowance() { allowance_.assign(mesh_.vertices.size(), 0.0); }
  double scale(std::size_t v) const { return scale_[v]; }

 private:
  struct Score {
    double min;     // smallest affected corner
    double energy;  // soft-min energy of the affected corners
  };
  Score score(const detail::VertexStar& st, const Vec3& p, double shift) {
    return {local_min(st, p), soft_energy(st, p, shift)};
  }
  //! Moves v to (the placement of) q if that raises its smallest corner, or,
  //! with `smooth`, lowers the soft-min energy without lowering it.
  bool try_move(const detail::VertexStar& st, const Vec3& q, bool free_boundary, double shift, bool smooth,
                Score& current) {
    const std::size_t v = st.v;
    Vec3 to;
    if (!place(v, q, free_boundary, to)) return false;
    const double m = local_min(st, to);
    if (m < current.min) return false;
    double e = current.energy;
    if (smooth) {  // lower the energy, keeping the smallest corner
      e = soft_energy(st, to, shift);
      if (!(e < current.energy - 1e-12 * std::abs(current.energy))) return false;
    } else if (!(m > current.min + kGain)) {  // raise the smallest corner
      return false;
    } else {
      e = soft_energy(st, to, shift);
    }
    mesh_.vertices[v] = to;
    current = {m, e};
    return true;
  }
  bool line_search(const detail::VertexStar& st, const Vec3& dir, double scale, bool free_boundary, double shift,
                   Score& current) {
    const Vec3 p = mesh_.vertices[st.v];
    double step = 0.25 * scale;
    for (int k = 0; k < 14; ++k, step *= 0.5)
      if (try_move(st, p + step * dir, free_boundary, shift, true, current)) return true;
    return false;
  }
  bool pattern_search(const detail::VertexStar& st, double scale, bool free_boundary, double shift, Score& current) {
    const Vec3 p = mesh_.vertices[st.v];
    for (double step = 0.1 * scale; step > 1e-4 * scale; step *= 0.25)
      for (int d = 0; d < 14; ++d) {
        Vec3 dir = Vec3::Zero();
        if (d < 6) dir[d / 2] = d % 2 ? -1.0 : 1.0;
        else dir = Vec3((d - 6) & 1 ? -1.0 : 1.0, (d - 6) & 2 ? -1.0 : 1.0, (d - 6) & 4 ? -1.0 : 1.0) / std::sqrt(3.0);
        if (try_move(st, p + step * dir, free_boundary, shift, false, current)) return true;
      }
    return false;
  }
  double edge_scale(std::size_t v) const {
    double s = 0;
    for (int w : topo_.neighbors[v]) s += (mesh_.vertices[idx(w)] - mesh_.vertices[v]).norm();
    return s / static_cast<double>(std::max<std::size_t>(1, topo_.neighbors[v].size()));
  }

  HexMesh& mesh_;
  const detail::SurfaceProjector& surface_;
  detail::HexTopology topo_;
  std::vector<std::vector<HexCorner>> corners_;  // per vertex: the corners it affects
  std::vector<double> scale_;                 // per vertex: mean edge length at the start
  std::vector<double> allowance_;             // per boundary vertex: how far it may be off the surface (last resort, loose)
  std::vector<char> loose_;                   // per vertex: a loose boundary vertex (set_loose); empty: none
  double attraction_ = 0;                     // weight of a loose vertex's distance to the surface in its energy
  detail::CornerCache cache_;                 // corner determinants and edge units (see refresh_corners)
};


std::size_t count_inverted(const std::vector<double>& sj) {
  return static_cast<std::size_t>(std::count_if(sj.begin(), sj.end(), [](double q) { return q <= 0; }));
}

//! How a run of sweeps picks its vertices and when it stops.
struct SweepRule {
  double threshold;        // the vertices of the hexahedra under this scaled Jacobian are visited ...
  int max_sweeps;          // ... in at most this many sweeps
  bool free_boundary;      // boundary vertices within their allowance of the surface (else they slide on it)
  double average_gain = 0; // > 0: stop when a sweep lowers the deficit (sum of threshold - q) by less than
                           // this per hexahedron (and does not raise the minimum); else by less than kSweepGain
};

//! Sweeps over the vertices of the hexahedra under the rule's threshold,
//! worst first. Returns the number of sweeps.
int sweep(Raiser& raiser, HexMesh& mesh, const SweepRule& rule, std::size_t& moves) {
  const detail::HexTopology& topo = raiser.topology();
  raiser.refresh_corners();
  double last_min = min_scaled_jacobian(raiser.qualities());
  int s = 0;
  while (s < rule.max_sweeps) {
    ++s;
    const std::vector<double> sj = raiser.qualities();
    std::vector<double> worst(mesh.vertices.size(), 2.0);
    double deficit_before = 0;
    for (std::size_t h = 0; h < sj.size(); ++h)
      if (sj[h] < rule.threshold) {
        deficit_before += rule.threshold - sj[h];
        for (int v : mesh.hexes[h]) worst[idx(v)] = std::min(worst[idx(v)], sj[h]);
      }
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t v = 0; v < worst.size(); ++v)
      if (worst[v] < 2.0) order.emplace_back(worst[v], v);
    if (order.empty()) break;
    std::sort(order.begin(), order.end());
    std::vector<std::size_t> vertices(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) vertices[i] = order[i].second;
    std::vector<std::size_t> moved(mesh.vertices.size(), 0);
    detail::gauss_seidel_sweep(mesh, topo, vertices,
                               [&](std::size_t v) { moved[v] = raiser.visit(v, rule.free_boundary); });
    for (std::size_t m : moved) moves += m;
    const std::vector<double> after = raiser.qualities();
    double deficit_after = 0;
    for (double q : after) deficit_after += std::max(0.0, rule.threshold - q);
    const double now = min_scaled_jacobian(after);
    const double gain = rule.average_gain > 0 ? rule.average_gain * static_cast<double>(after.size()) : kSweepGain;
    const bool gained = now > last_min + kSweepGain || deficit_after < deficit_before - gain;
    last_min = now;
    if (!gained) break;
  }
  return s;
}

//! The vertices of the hexahedra under the margin, grown by `rings` rings
//! of edge neighbours, in index order; boundary vertices of the patch with no
//! allowance yet may slide on the surface (allowance: their distance now).
std::vector<std::size_t> repair_patch(Raiser& raiser, const HexMesh& mesh, const std::vector<double>& sj, int rings,
                                      double margin) {
  const detail::HexTopology& topo = raiser.topology();
  std::vector<char> in_patch(mesh.vertices.size(), 0);
  for (std::size_t h = 0; h < sj.size(); ++h)
    if (sj[h] <= margin)
      for (int v : mesh.hexes[h]) in_patch[idx(v)] = 1;
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<char> grown = in_patch;
    for (std::size_t v = 0; v < in_patch.size(); ++v)
      if (in_patch[v])
        for (int w : topo.neighbors[v]) grown[idx(w)] = 1;
    in_patch = std::move(grown);
  }
  std::vector<std::size_t> patch;
  for (std::size_t v = 0; v < in_patch.size(); ++v)
    if (in_patch[v]) {
      patch.push_back(v);
      if (topo.on_boundary[v] && raiser.allowance(v) == 0)
        raiser.set_allowance(v, raiser.distance_to_surface(mesh.vertices[v]));
    }
  return patch;
}

//! Resets the inside of the patch (vertices off the surface whose
//! neighbours are all in the patch) by Jacobi iterations of the mean of the
//! neighbours: a star folded over (an interior vertex whose opposite
//! neighbours ended on the same side, no position of its own valid) opens.
void relax_patch_interior(const Raiser& raiser, HexMesh& mesh, const std::vector<std::size_t>& patch, int iterations) {
  const detail::HexTopology& topo = raiser.topology();
  std::vector<char> in_patch(mesh.vertices.size(), 0);
  for (std::size_t v : patch) in_patch[v] = 1;
  std::vector<std::size_t> inner;
  for (std::size_t v : patch) {
    bool all = !topo.on_boundary[v];
    for (int w : topo.neighbors[v]) all = all && in_patch[idx(w)];
    if (all) inner.push_back(v);
  }
  for (int it = 0; it < iterations; ++it) {
    std::vector<Vec3> next(inner.size());
    for (std::size_t i = 0; i < inner.size(); ++i) {
      Vec3 c = Vec3::Zero();
      for (int w : topo.neighbors[inner[i]]) c += mesh.vertices[idx(w)];
      next[i] = c / static_cast<double>(topo.neighbors[inner[i]].size());
    }
    for (std::size_t i = 0; i < inner.size(); ++i) mesh.vertices[inner[i]] = next[i];
  }
}

}  // namespace

RaiseMinScaledJacobianReport raise_min_scaled_jacobian(HexMesh& mesh, const Mesh& surface,
                                                       const RaiseMinScaledJacobianOptions& options) {
  const detail::SurfaceProjector projector(surface);
  return detail::raise_min_scaled_jacobian(mesh, projector, options);
}

RaiseMinScaledJacobianReport detail::raise_min_scaled_jacobian(HexMesh& mesh, const SurfaceProjector& projector,
                                                               const RaiseMinScaledJacobianOptions& options) {
  RaiseMinScaledJacobianReport report;
  Raiser raiser(mesh, projector);
  raiser.init_allowance();
  std::vector<double> sj = scaled_jacobians(mesh);
  report.min_before = min_scaled_jacobian(sj);
  report.num_inverted_before = count_inverted(sj);
  report.sweeps = sweep(raiser, mesh, {options.threshold, options.sweeps, false}, report.num_moves);
  sj = scaled_jacobians(mesh);
  // the joint repair of the hexahedra under `margin` (last resort, below)
  const auto repair_worst = [&](double margin) {
    // the patch grown by the rings of kRepairs, tried in turn from the same
    // start, the best kept; the boundary vertices of the hexahedra under the margin
    // may leave the surface (a vertex already off it keeps its distance)
    const detail::HexTopology& topo = raiser.topology();
    for (std::size_t h = 0; h < sj.size(); ++h)
      if (sj[h] <= margin)
        for (int v : mesh.hexes[h])
          if (topo.on_boundary[idx(v)])
            raiser.set_allowance(idx(v), std::max(options.max_off_surface * raiser.scale(idx(v)),
                                                  raiser.distance_to_surface(mesh.vertices[idx(v)])));
    const std::vector<Vec3> kept = mesh.vertices;
    std::vector<Vec3> best = kept;
    double best_min = min_scaled_jacobian(sj);
    for (const Repair& repair : kRepairs) {
      mesh.vertices = kept;
      const std::vector<std::size_t> patch = repair_patch(raiser, mesh, sj, repair.rings, margin);
      if (repair.laplacian > 0) relax_patch_interior(raiser, mesh, patch, repair.laplacian);
      report.untangle_steps += raiser.untangle_patch(patch, kUntangleSteps);
      report.sweeps += sweep(raiser, mesh, {margin, options.sweeps, true}, report.num_moves);
      const double now = min_scaled_jacobian(scaled_jacobians(mesh));
      if (now > best_min) best_min = now, best = mesh.vertices;
      if (best_min > margin) break;
    }
    mesh.vertices = std::move(best);
    sj = scaled_jacobians(mesh);
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      if (topo.on_boundary[v] && (mesh.vertices[v] - kept[v]).squaredNorm() > 0) ++report.num_off_surface;
  };
  if (options.free_boundary_for_inverted && min_scaled_jacobian(sj) <= kMargin) repair_worst(kMargin);
  // few elements still under repair_below: the same joint repair (a local
  // fold of the boundary's quad layout that one vertex at a time cannot open)
  if (const double below = options.repair_below; below > kMargin && min_scaled_jacobian(sj) <= below) {
    const auto n = std::count_if(sj.begin(), sj.end(), [below](double q) { return q <= below; });
    if (static_cast<std::size_t>(n) <= options.repair_max_hexes) {
      repair_worst(below);
      report.repaired_worst = static_cast<std::size_t>(n);
    }
  }
  if (options.quality_sweeps > 0) {
    // the boundary vertices of the hexahedra under loose_below leave the
    // hard constraint for an attraction to the surface (thesis D.6: the
    // edge-cone rectification's surface attraction): where the surface
    // curves more than the boundary quads can follow, a corner on the
    // surface cannot open without leaving it a little
    std::vector<Vec3> before;
    if (options.loose_attraction > 0) {
      before = mesh.vertices;
      const detail::HexTopology& topo = raiser.topology();
      for (std::size_t h = 0; h < sj.size(); ++h)
        if (sj[h] < options.loose_below)
          for (int v : mesh.hexes[h])
            if (topo.on_boundary[idx(v)])
              raiser.set_loose(idx(v), options.max_off_surface * raiser.scale(idx(v)), options.loose_attraction);
    }
    report.sweeps += sweep(raiser, mesh, {options.quality_threshold, options.quality_sweeps, false, options.quality_gain},
                           report.num_moves);
    sj = scaled_jacobians(mesh);
    for (std::size_t v = 0; v < before.size(); ++v)
      if (raiser.loose(v) && (mesh.vertices[v] - before[v]).squaredNorm() > 0) ++report.num_loose_moved;
  }
  report.min_after = min_scaled_jacobian(sj);
  report.num_inverted_after = count_inverted(sj);
  return report;
}

}  // namespace subfab
