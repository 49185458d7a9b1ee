// SPDX-License-Identifier: GPL-3.0-or-later
//! \file worst_raiser.h
//! Private: the joint optimisation of a patch of vertices for its worst
//! scaled Jacobian (gradient ascent on the soft minimum of its corners,
//! boundary vertices sliding on the surface), shared by
//! raise_worst_scaled_jacobian() (its patches around the worst hexahedra) and
//! pull_boundary_to_surface() (a held boundary vertex put on the surface, its
//! neighbourhood re-optimised). docs/hexmesh.md, "Worst elements jointly".
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "hex/hex_corners.h"
#include "hex/hex_topology.h"
#include "hex/surface_projector.h"
#include "subfab/hex/raise_worst_scaled_jacobian.h"
#include "subfab/hex/scaled_jacobian.h"

namespace subfab::detail {

//! See raise_worst_scaled_jacobian.h for the ascent, its options and its guard.
class WorstRaiser {
 public:
  static constexpr double kOnSurface = 1e-9;  // a boundary vertex within this fraction of its mean edge is on the surface
  static constexpr int kHalvings = 12;        // backtracking: step lengths 1, 1/2, ... of the scaled gradient
  static constexpr int kContinuation = 3;     // sharpness, 2x, 4x

  WorstRaiser(HexMesh& mesh, const SurfaceProjector& surface, const RaiseWorstScaledJacobianOptions& options)
      : mesh_(mesh),
        surface_(surface),
        options_(options),
        topo_(hex_topology(mesh)),
        corners_(vertex_corners(mesh)),
        origin_(mesh.vertices),
        slot_(mesh.hexes.size(), -1) {
    VertexAllowances a = vertex_allowances(mesh, topo_, surface, kOnSurface);
    scale_ = std::move(a.scale);
    allowance_ = std::move(a.allowance);  // 0: slides on the surface
  }

  const HexTopology& topology() const { return topo_; }
  //! Boundary vertex v may leave the surface by `fraction` of its mean edge
  //! (or stay as far as it already is).
  void loosen(std::size_t v, double fraction) {
    if (topo_.on_boundary[v]) allowance_[v] = std::max(allowance_[v], fraction * scale_[v]);
  }

  //! A boundary vertex's state, to undo pin().
  struct Pinned {
    std::size_t v;
    Vec3 position, origin;
    double allowance;
  };
  //! Puts boundary vertex v at p: on the surface (p its own closest point)
  //! it slides from then on (max_slide counted from p), off the surface it
  //! may move but never farther from it. Returns what unpin() restores.
  Pinned pin(std::size_t v, const Vec3& p) {
    const Pinned old{v, mesh_.vertices[v], origin_[v], allowance_[v]};
    mesh_.vertices[v] = p;
    origin_[v] = p;
    const double d = (surface_.closest_point(p) - p).norm();
    allowance_[v] = d > kOnSurface * scale_[v] ? d : 0.0;
    return old;
  }
  void unpin(const Pinned& old) {
    mesh_.vertices[old.v] = old.position;
    origin_[old.v] = old.origin;
    allowance_[old.v] = old.allowance;
  }

  //! Optimises the patch (vertex indices, sorted): from where it is, then
  //! (with `restarts`) from its inside relaxed by `restarts` Jacobi
  //! iterations; the positions with the larger smallest corner are kept,
  //! never worse than at the start. Returns whether its smallest corner rose;
  //! adds the accepted steps to `steps`.
  bool raise(const std::vector<std::size_t>& patch, std::size_t& steps) {
    // the hexahedra whose corners the patch moves
    hexes_.clear();
    for (std::size_t v : patch) hexes_.insert(hexes_.end(), topo_.vertex_hexes[v].begin(), topo_.vertex_hexes[v].end());
    std::sort(hexes_.begin(), hexes_.end());
    hexes_.erase(std::unique(hexes_.begin(), hexes_.end()), hexes_.end());
    for (std::size_t j = 0; j < hexes_.size(); ++j) slot_[idx(hexes_[j])] = static_cast<int>(j);
    alpha_.resize(8 * hexes_.size());
    std::vector<Vec3> original(patch.size());
    for (std::size_t i = 0; i < patch.size(); ++i) original[i] = mesh_.vertices[patch[i]];
    evaluate();
    const double first = min_scaled_jacobian(alpha_);
    double result = ascend(patch, steps);
    if (options_.restarts > 0) {
      std::vector<Vec3> kept(patch.size());
      for (std::size_t i = 0; i < patch.size(); ++i) kept[i] = mesh_.vertices[patch[i]];
      relax(patch, options_.restarts);
      std::size_t more = 0;
      const double again = ascend(patch, more);
      if (again > result) {
        result = again, steps += more;
      } else {
        for (std::size_t i = 0; i < patch.size(); ++i) mesh_.vertices[patch[i]] = kept[i];
      }
    }
    if (!(result > first))  // never worse than at the start
      for (std::size_t i = 0; i < patch.size(); ++i) mesh_.vertices[patch[i]] = original[i];
    for (int h : hexes_) slot_[idx(h)] = -1;
    return result > first;
  }

 private:
  static std::size_t idx(int v) { return static_cast<std::size_t>(v); }
  //! Jacobi iterations on the inside of the patch (vertices whose
  //! neighbours are all in it): an interior vertex to the mean of its
  //! neighbours, a boundary vertex to the mean of its boundary neighbours,
  //! placed as a step (onto the surface). The rim stays.
  void relax(const std::vector<std::size_t>& patch, int iterations) {
    std::vector<char> in(mesh_.vertices.size(), 0);
    for (std::size_t v : patch) in[v] = 1;
    std::vector<std::size_t> inner;
    for (std::size_t v : patch) {
      bool all = true;
      for (int w : topo_.neighbors[v]) all = all && in[idx(w)];
      if (all) inner.push_back(v);
    }
    std::vector<Vec3> next(inner.size());
    for (int it = 0; it < iterations; ++it) {
      for (std::size_t i = 0; i < inner.size(); ++i) {
        const std::size_t v = inner[i];
        const auto& around = topo_.on_boundary[v] ? topo_.boundary_neighbors[v] : topo_.neighbors[v];
        Vec3 c = Vec3::Zero();
        for (int w : around) c += mesh_.vertices[idx(w)];
        next[i] = place(v, mesh_.vertices[v], c / static_cast<double>(std::max<std::size_t>(1, around.size())));
      }
      for (std::size_t i = 0; i < inner.size(); ++i) mesh_.vertices[inner[i]] = next[i];
    }
  }

  //! Gradient ascent on the soft minimum from the patch's current positions
  //! (see the header); leaves the positions with the largest smallest corner
  //! met and returns that corner.
  double ascend(const std::vector<std::size_t>& patch, std::size_t& steps) {
    std::vector<Vec3> dir(patch.size()), start(patch.size());
    double beta = options_.sharpness;
    int level = 0;  // of the continuation: beta = sharpness x 2^level
    evaluate();
    double value = soft_min(beta);
    double worst = min_scaled_jacobian(alpha_);
    double last_t = 1e300;
    std::vector<Vec3> best(patch.size());
    for (std::size_t i = 0; i < patch.size(); ++i) best[i] = mesh_.vertices[patch[i]];
    for (int it = 0; level < kContinuation; ++it) {
      if (it == (level + 1) * options_.max_steps / kContinuation) {  // next level of the continuation
        ++level, beta *= 2;
        for (std::size_t i = 0; i < patch.size(); ++i) mesh_.vertices[patch[i]] = best[i];
        evaluate();
        value = soft_min(beta);
        last_t = 1e300;
        continue;
      }
      // ascent direction of the soft minimum: per vertex, the tangent part
      // on the surface, scaled by its squared mean edge
      weights(beta);
      double longest = 0;  // largest step over the patch, in mean edges
      for (std::size_t i = 0; i < patch.size(); ++i) {
        const std::size_t v = patch[i];
        Vec3 g = Vec3::Zero(), dg;
        for (const HexCorner& k : corners_[v]) {
          corner_determinant_gradient(mesh_, k, static_cast<int>(v), dg);
          g += weight_[8 * idx(slot_[idx(k.hex)]) + idx(k.corner)] * dg;
        }
        if (topo_.on_boundary[v] && allowance_[v] == 0.0) {
          Vec3 normal;
          surface_.closest_point(mesh_.vertices[v], &normal);
          g -= g.dot(normal) * normal;
        }
        dir[i] = scale_[v] * scale_[v] * g;
        longest = std::max(longest, dir[i].norm() / scale_[v]);
        start[i] = mesh_.vertices[v];
      }
      bool moved = false;
      if (longest > 0) {
        double t = std::min(options_.max_step / longest, 4 * last_t);
        for (int k = 0; k < kHalvings && !moved; ++k, t *= 0.5) {
          for (std::size_t i = 0; i < patch.size(); ++i)
            mesh_.vertices[patch[i]] = place(patch[i], start[i], start[i] + t * dir[i]);
          {
            evaluate();
            const double now = min_scaled_jacobian(alpha_);
            const double soft = soft_min(beta);
            if (soft > value + 1e-12 * std::abs(value)) {
              value = soft, moved = true, last_t = t;
              if (now > worst) {
                worst = now;
                for (std::size_t i = 0; i < patch.size(); ++i) best[i] = mesh_.vertices[patch[i]];
              }
              break;
            }
          }
          for (std::size_t i = 0; i < patch.size(); ++i) mesh_.vertices[patch[i]] = start[i];
        }
      }
      if (moved) {
        ++steps;
        continue;
      }
      // no step: sharper soft minimum (closer to the true one)
      ++level, beta *= 2;
      it = level * options_.max_steps / kContinuation;
      for (std::size_t i = 0; i < patch.size(); ++i) mesh_.vertices[patch[i]] = best[i];
      evaluate();
      value = soft_min(beta);
      last_t = 1e300;
    }
    for (std::size_t i = 0; i < patch.size(); ++i) mesh_.vertices[patch[i]] = best[i];
    return worst;
  }

  //! Where a step of v from `from` to q really goes: a sliding vertex onto
  //! the surface (it stays at `from` beyond max_slide), a vertex off the
  //! surface no farther from it than it was.
  Vec3 place(std::size_t v, const Vec3& from, const Vec3& q) const {
    if (!topo_.on_boundary[v]) return q;
    if (allowance_[v] == 0.0) {
      const Vec3 onto = surface_.closest_point(q);
      return (onto - origin_[v]).norm() <= options_.max_slide * scale_[v] ? onto : from;
    }
    const Vec3 c = surface_.closest_point(q);
    const double d = (q - c).norm();
    return d > allowance_[v] ? Vec3(c + (allowance_[v] / d) * (q - c)) : q;
  }

  void evaluate() {
    for (std::size_t j = 0; j < hexes_.size(); ++j)
      for (int c = 0; c < 8; ++c) alpha_[8 * j + idx(c)] = corner_determinant(mesh_, {hexes_[j], c});
  }
  //! -1/beta log sum exp(-beta alpha), shifted by the minimum.
  double soft_min(double beta) const {
    const double m = min_scaled_jacobian(alpha_);
    double s = 0;
    for (double a : alpha_) s += std::exp(-beta * (a - m));
    return m - std::log(s) / beta;
  }
  //! d soft_min / d alpha_c for every corner.
  void weights(double beta) {
    const double m = min_scaled_jacobian(alpha_);
    weight_.resize(alpha_.size());
    double s = 0;
    for (std::size_t c = 0; c < alpha_.size(); ++c) s += weight_[c] = std::exp(-beta * (alpha_[c] - m));
    for (double& w : weight_) w /= s;
  }

  HexMesh& mesh_;
  const SurfaceProjector& surface_;
  const RaiseWorstScaledJacobianOptions& options_;
  HexTopology topo_;
  std::vector<std::vector<HexCorner>> corners_;  // per vertex: the corners it moves
  std::vector<Vec3> origin_;       // per vertex: its position at the start (max_slide)
  std::vector<double> scale_;      // per vertex: mean edge length at the start
  std::vector<double> allowance_;  // per boundary vertex: 0 on the surface (slides), else its distance (never farther)
  std::vector<int> slot_;          // per hexahedron: its index in hexes_, -1 outside the patch
  std::vector<int> hexes_;         // the patch's hexahedra
  std::vector<double> alpha_, weight_;  // per corner of hexes_ (8 j + c)
};

}  // namespace subfab::detail
