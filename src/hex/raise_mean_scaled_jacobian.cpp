// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/raise_mean_scaled_jacobian.h"

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

constexpr double kFirstStep = 0.25;  // longest trial step, fraction of the vertex's mean edge
constexpr double kMinStep = 1e-4;    // the remembered step never shrinks under this fraction of the mean edge
constexpr int kPatience = 5;         // stop after this many sweeps in a row that raise the best average by < min_gain
                                     // (2 until session 32: the first sweeps can lower the average, a boundary vertex
                                     // sliding 0.25 of its edge, and the capsule of the tests stopped after 2 sweeps)
constexpr double kOnSurface = 1e-9;  // a boundary vertex within this fraction of its mean edge is on the surface


class MeanRaiser {
 public:
  MeanRaiser(HexMesh& mesh, const detail::SurfaceProjector& surface, const RaiseMeanScaledJacobianOptions& options)
      : mesh_(mesh), surface_(surface), options_(options), topo_(detail::hex_topology(mesh)) {
    const std::size_t n = mesh.vertices.size();
    detail::VertexAllowances a = detail::vertex_allowances(mesh, topo_, surface, kOnSurface);
    scale_ = std::move(a.scale);
    allowance_ = std::move(a.allowance);  // 0: slides on the surface
    step_.assign(n, 0.0);
    for (std::size_t v = 0; v < n; ++v) step_[v] = kFirstStep * scale_[v];
    last_move_.assign(n, 0);
    origin_ = mesh.vertices;
    cache_ = detail::corner_cache(mesh);
  }

  const detail::HexTopology& topology() const { return topo_; }
  std::vector<double> qualities() const { return detail::hex_qualities(cache_); }
  void set_floor(double floor) { floor_ = floor; }

  //! Visits v (see the header); returns the number of accepted steps.
  std::size_t visit(std::size_t v, int sweep) {
    const double scale = scale_[v];
    if (!(scale > 0)) return 0;
    if (topo_.on_boundary[v] && !options_.slide_boundary) return 0;
    if (!active(v, sweep)) return 0;
    thread_local detail::VertexStar st;
    thread_local std::vector<double> bound;  // per hexahedron of v: the scaled Jacobian a move must keep
    detail::build_vertex_star(st, mesh_, topo_.vertex_hexes[v], v, options_.sharpness, &cache_);
    const std::size_t nh = st.hexes->size();
    detail::evaluate_star(mesh_, st);
    bound.resize(nh);
    for (std::size_t j = 0; j < nh; ++j) bound[j] = std::min(detail::star_hex_quality(st, j), floor_);
    const bool slides = topo_.on_boundary[v] && allowance_[v] == 0.0;
    const bool free_near = topo_.on_boundary[v] && allowance_[v] > 0.0;
    double current = energy_at(st, mesh_.vertices[v], nullptr).energy;
    const Vec3 start = mesh_.vertices[v];
    const double start_energy = current;
    std::size_t moves = 0;
    for (int it = 0; it < options_.moves_per_visit; ++it) {
      const Vec3 p = mesh_.vertices[v];
      Vec3 grad = gradient_at(st, p);
      if (slides) {
        Vec3 normal;
        surface_.closest_point(p, &normal);
        grad -= grad.dot(normal) * normal;
      }
      const double g = grad.norm();
      if (!(g > 0)) break;
      const Vec3 dir = -grad / g;
      // halving until a valid point lowers the energy, from twice the last
      // step the vertex took (a quarter of its mean edge at first)
      double t = std::min(kFirstStep * scale, 2 * step_[v]), found_t = 0, found_e = current;
      Vec3 found_p = p;
      for (int k = 0; k < 16; ++k, t *= 0.5) {
        Vec3 q;
        if (!place(v, p + t * dir, slides, free_near, q)) continue;
        const Value val = energy_at(st, q, bound.data());
        if (!(val.valid && val.energy < current - 1e-14 * std::abs(current))) continue;
        found_t = t, found_e = val.energy, found_p = q;
        break;
      }
      if (found_t == 0) break;
      // the parabola through E(0), E'(0) = -g and E(t)
      const double curvature = found_e - current + g * found_t;
      if (curvature > 0) {
        const double t_star = g * found_t * found_t / (2 * curvature);
        if (t_star > 0.05 * found_t && t_star < 4 * found_t && std::abs(t_star - found_t) > 1e-3 * found_t) {
          Vec3 q;
          if (place(v, p + t_star * dir, slides, free_near, q)) {
            const Value val = energy_at(st, q, bound.data());
            if (val.valid && val.energy < found_e) found_e = val.energy, found_p = q;
          }
        }
      }
      step_[v] = std::max((found_p - p).norm(), kMinStep * scale);
      mesh_.vertices[v] = found_p;
      current = found_e;
      ++moves;
    }
    if (moves > 0 && options_.over_relaxation != 1.0) {
      // over-relaxation (nonlinear SOR): the visit's displacement stretched,
      // kept if it is valid and still lowers v's energy from where it started
      const Vec3 d = mesh_.vertices[v] - start;
      Vec3 q;
      if (place(v, start + options_.over_relaxation * d, slides, free_near, q)) {
        const Value val = energy_at(st, q, bound.data());
        if (val.valid && val.energy < start_energy) mesh_.vertices[v] = q;
      }
    }
    if (moves > 0) detail::store_star(mesh_, st, cache_);
    if ((mesh_.vertices[v] - start).norm() > options_.active_move * scale) last_move_[v] = sweep;
    return moves;
  }

 private:
  //! Where a step of v to q really goes: onto the surface for a sliding
  //! vertex; false for a loose vertex it would take farther off the surface.
  bool place(std::size_t v, const Vec3& q, bool slides, bool free_near, Vec3& out) const {
    if (slides) {
      out = surface_.closest_point(q);
      return (out - origin_[v]).norm() <= options_.max_slide * scale_[v];
    }
    if (free_near && (surface_.closest_point(q) - q).norm() > allowance_[v]) return false;
    out = q;
    return true;
  }

  //! Whether v is visited in `sweep` (from 1): always in the first; then
  //! only if a vertex of its hexahedra (v included) moved by more than
  //! active_move of its mean edge in this sweep (visited before v) or the
  //! previous one. Reads only the vertices of v's hexahedra, which the waves
  //! order as the serial sweep does: deterministic.
  bool active(std::size_t v, int sweep) const {
    if (sweep <= 1) return true;
    for (int h : topo_.vertex_hexes[v])
      for (int w : mesh_.hexes[idx(h)])
        if (last_move_[idx(w)] >= sweep - 1) return true;
    return false;
  }

  struct Value {
    double energy;  // v's part of E, up to the constant: sum over its hexahedra of log sum exp(-beta alpha) / beta
    bool valid;     // every hexahedron keeps its bound (always true without bounds)
  };
  //! v's part of E with v at p; with `bound` (per hexahedron of the star),
  //! whether every hexahedron keeps its scaled Jacobian >= its bound.
  Value energy_at(const detail::VertexStar& st, const Vec3& p, const double* bound) {
    const Vec3 old = mesh_.vertices[st.v];
    mesh_.vertices[st.v] = p;
    detail::evaluate_star(mesh_, st);
    mesh_.vertices[st.v] = old;
    const double beta = options_.sharpness;
    double e = 0;
    bool valid = true;
    for (std::size_t j = 0; j < st.hexes->size(); ++j) {
      double s = 0, q = st.fixed_min[j];
      for (std::size_t i = 0; i < 8; ++i) {
        const int c = st.slot[8 * j + i];
        if (c < 0) {
          s += st.fixed_exp[8 * j + i];
        } else {
          const double a = st.values[idx(c)];
          s += std::exp(-beta * a);
          q = std::min(q, a);
        }
      }
      e += std::log(s);
      if (bound && q < bound[j]) valid = false;
    }
    return {e / beta, valid};
  }

  //! The gradient of v's part of E with respect to v's position, at p:
  //! dE/dv = -sum over moved corners of w dalpha/dv, w = exp(-beta alpha) /
  //! sum over its hexahedron's corners of exp(-beta alpha'); a corner's
  //! derivative along its unit edge u from v (length L) to a neighbour is
  //! -(I - u u^T) / L times the cofactor of that edge (e1 x e2 for e0 ...),
  //! gathered per neighbour first. Degenerate corners (constant -1) add 0.
  Vec3 gradient_at(const detail::VertexStar& st, const Vec3& p) {
    const Vec3 old = mesh_.vertices[st.v];
    mesh_.vertices[st.v] = p;
    detail::evaluate_star(mesh_, st);
    mesh_.vertices[st.v] = old;
    thread_local std::vector<Vec3> gathered;  // per neighbour: sum of sign x w x cofactor
    gathered.assign(st.neighbours.size(), Vec3::Zero());
    const double beta = options_.sharpness;
    for (std::size_t j = 0; j < st.hexes->size(); ++j) {
      double sum = 0;
      for (std::size_t i = 0; i < 8; ++i) {
        const int c = st.slot[8 * j + i];
        sum += c < 0 ? st.fixed_exp[8 * j + i] : std::exp(-beta * st.values[idx(c)]);
      }
      for (std::size_t i = 0; i < 8; ++i) {
        const int c = st.slot[8 * j + i];
        if (c < 0) continue;
        const detail::VertexStar::Moved& m = st.moved[idx(c)];
        Vec3 e[3];
        if (!detail::star_corner_edges(st, idx(c), e)) continue;
        const double w = std::exp(-beta * st.values[idx(c)]) / sum;
        const Vec3 cofactor[3] = {e[1].cross(e[2]), e[2].cross(e[0]), e[0].cross(e[1])};
        for (std::size_t k = 0; k < 3; ++k)
          if (m.neighbour[k] >= 0) gathered[idx(m.neighbour[k])] += (m.sign[k] * w) * cofactor[k];
      }
    }
    Vec3 grad = Vec3::Zero();
    for (std::size_t s = 0; s < st.neighbours.size(); ++s) {
      if (st.zero[s]) continue;
      const Vec3& u = st.units[s];
      const double length = (mesh_.vertices[idx(st.neighbours[s])] - p).norm();
      // dE/dv = -sum w dalpha/dv, dalpha/dv = sum sign (-(I - u u^T) / L) cofactor
      grad += (gathered[s] - u * u.dot(gathered[s])) / length;
    }
    return grad;
  }

  HexMesh& mesh_;
  const detail::SurfaceProjector& surface_;
  const RaiseMeanScaledJacobianOptions& options_;
  detail::HexTopology topo_;
  std::vector<double> scale_;      // per vertex: mean edge length at the start
  std::vector<Vec3> origin_;       // per vertex: its position at the start (a sliding vertex stays within max_slide)
  std::vector<int> last_move_;     // per vertex: the last sweep in which it moved by more than active_move (0: none)
  std::vector<double> step_;       // per vertex: length of its last accepted step (visit writes only its own)
  std::vector<double> allowance_;  // per boundary vertex: 0 on the surface (slides), else its distance (never farther)
  double floor_ = 0;
  detail::CornerCache cache_;
};

}  // namespace

RaiseMeanScaledJacobianReport detail::raise_mean_scaled_jacobian(HexMesh& mesh, const SurfaceProjector& projector,
                                                                 const RaiseMeanScaledJacobianOptions& options) {
  RaiseMeanScaledJacobianReport report;
  MeanRaiser raiser(mesh, projector, options);
  std::vector<double> q = raiser.qualities();
  report.avg_before = report.avg_after = mean_scaled_jacobian(q);
  report.min_before = report.min_after = min_scaled_jacobian(q);
  raiser.set_floor(std::max(options.floor, report.min_before));
  std::vector<std::size_t> order(mesh.vertices.size());
  for (std::size_t v = 0; v < order.size(); ++v) order[v] = v;
  const auto waves = detail::gauss_seidel_schedule(mesh, raiser.topology(), order);
  std::vector<std::size_t> moved(mesh.vertices.size(), 0);
  // the positions with the best average are kept: the sweeps lower the
  // surrogate E, not the average itself, which can dip (over-relaxation)
  std::vector<Vec3> best = mesh.vertices;
  double best_avg = report.avg_before;
  int stalled = 0;
  while (report.sweeps < options.max_sweeps && stalled < kPatience) {
    ++report.sweeps;
    detail::run_waves(waves, [&](std::size_t v) { moved[v] = raiser.visit(v, report.sweeps); });
    for (std::size_t m : moved) report.num_moves += m;
    q = raiser.qualities();
    const double avg = mean_scaled_jacobian(q);
    stalled = avg > best_avg + options.min_gain ? 0 : stalled + 1;
    if (avg > best_avg) best_avg = avg, best = mesh.vertices;
  }
  mesh.vertices = std::move(best);
  q = scaled_jacobians(mesh);
  report.avg_after = mean_scaled_jacobian(q);
  report.min_after = min_scaled_jacobian(q);
  return report;
}

RaiseMeanScaledJacobianReport raise_mean_scaled_jacobian(HexMesh& mesh, const Mesh& surface,
                                                         const RaiseMeanScaledJacobianOptions& options) {
  const detail::SurfaceProjector projector(surface);
  return detail::raise_mean_scaled_jacobian(mesh, projector, options);
}

}  // namespace subfab
