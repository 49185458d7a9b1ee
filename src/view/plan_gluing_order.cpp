// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/view/plan_gluing_order.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

// Ray positions inside a grid cell, as fractions of the spacing: off the
// cell centre by irrational-looking amounts, so rays of a model with round
// coordinates do not run along its edges.
constexpr double kJitterU = 0.5137;
constexpr double kJitterV = 0.4711;

//! Where one block's material lies along one ray: the middles of its first
//! and last intervals (crossings paired in depth order).
struct Extent {
  std::size_t block;
  double lowest_mid, highest_mid;
};

//! Crossings of every block with every ray parallel to axis k.
class RayGrid {
 public:
  RayGrid(const BoundingBox& box, double spacing, int k) : k_(k), u_((k + 1) % 3), v_((k + 2) % 3), h_(spacing) {
    u0_ = box.min[u_];
    v0_ = box.min[v_];
    nu_ = static_cast<int>(std::ceil(box.size()[u_] / h_)) + 1;
    nv_ = static_cast<int>(std::ceil(box.size()[v_] / h_)) + 1;
    hits_.resize(std::size_t(nu_) * nv_);
  }

  //! Records where the triangle (a, b, c) of `block` crosses the rays.
  void add_triangle(std::size_t block, const Vec3& a, const Vec3& b, const Vec3& c) {
    const double au = a[u_], av = a[v_], bu = b[u_], bv = b[v_], cu = c[u_], cv = c[v_];
    const double area = (bu - au) * (cv - av) - (bv - av) * (cu - au);
    if (std::abs(area) <= 1e-14 * h_ * h_) return;  // parallel to the rays
    const int i0 = std::max(0, int(std::ceil((std::min({au, bu, cu}) - u0_) / h_ - kJitterU)));
    const int i1 = std::min(nu_ - 1, int(std::floor((std::max({au, bu, cu}) - u0_) / h_ - kJitterU)));
    const int j0 = std::max(0, int(std::ceil((std::min({av, bv, cv}) - v0_) / h_ - kJitterV)));
    const int j1 = std::min(nv_ - 1, int(std::floor((std::max({av, bv, cv}) - v0_) / h_ - kJitterV)));
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j) {
        const double pu = u0_ + (i + kJitterU) * h_, pv = v0_ + (j + kJitterV) * h_;
        const double wa = ((bu - pu) * (cv - pv) - (bv - pv) * (cu - pu)) / area;
        const double wb = ((cu - pu) * (av - pv) - (cv - pv) * (au - pu)) / area;
        const double wc = 1.0 - wa - wb;
        if (wa < 0 || wb < 0 || wc < 0) continue;
        hits_[std::size_t(i) * nv_ + j].push_back({wa * a[k_] + wb * b[k_] + wc * c[k_], block});
      }
  }

  std::size_t num_rays() const { return hits_.size(); }

  //! The extents of the blocks on ray r (blocks crossed an odd number of
  //! times, where the ray grazes an edge, are left out).
  std::vector<Extent> extents(std::size_t r) const {
    std::vector<std::pair<double, std::size_t>> hits = hits_[r];
    std::sort(hits.begin(), hits.end(), [](const auto& x, const auto& y) {
      return x.second != y.second ? x.second < y.second : x.first < y.first;
    });
    std::vector<Extent> out;
    for (std::size_t s = 0; s < hits.size();) {
      std::size_t e = s;
      while (e < hits.size() && hits[e].second == hits[s].second) ++e;
      if ((e - s) % 2 == 0) {
        Extent x{hits[s].second, std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
        for (std::size_t q = s; q < e; q += 2) {
          if (hits[q + 1].first - hits[q].first <= 1e-9 * h_) continue;  // touching itself, no material
          const double mid = 0.5 * (hits[q].first + hits[q + 1].first);
          x.lowest_mid = std::min(x.lowest_mid, mid);
          x.highest_mid = std::max(x.highest_mid, mid);
        }
        if (x.lowest_mid <= x.highest_mid) out.push_back(x);
      }
      s = e;
    }
    return out;
  }

 private:
  int k_, u_, v_;
  double h_, u0_ = 0, v0_ = 0;
  int nu_ = 0, nv_ = 0;
  std::vector<std::vector<std::pair<double, std::size_t>>> hits_;  // per ray: (depth along k, block)
};

}  // namespace

std::string axis_label(int axis) {
  static const char* const kLabels[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  return axis >= 0 && axis < 6 ? kLabels[axis] : "";
}

int axis_index(const std::string& label) {
  for (int d = 0; d < 6; ++d)
    if (label == axis_label(d) || (d % 2 == 0 && label == axis_label(d).substr(1))) return d;
  return -1;
}

BlockingRelation compute_blocking(const std::vector<Mesh>& blocks, const GluingOptions& options) {
  if (options.resolution < 2 || options.resolution > 4096)
    throw InvalidArgumentError("gluing order: resolution must be in [2, 4096], got " +
                               std::to_string(options.resolution));
  const std::size_t n = blocks.size();
  BlockingRelation rel;
  rel.num_blocks = n;
  for (auto& b : rel.blocked) b.assign(n * n, false);
  std::vector<std::vector<Vec3>> points(n);
  BoundingBox all;
  for (std::size_t b = 0; b < n; ++b)
    for (const Vec3& p : blocks[b].vertices) {
      points[b].push_back(options.rotation * p);
      all.extend(points[b].back());
    }
  if (all.is_empty()) return rel;
  rel.ray_spacing = std::max(all.size().maxCoeff(), 1e-300) / options.resolution;
  for (int k = 0; k < 3; ++k) {
    RayGrid grid(all, rel.ray_spacing, k);
    for (std::size_t b = 0; b < n; ++b)
      for (const Triangle& t : blocks[b].faces) grid.add_triangle(b, points[b][t[0]], points[b][t[1]], points[b][t[2]]);
    // Per ray, which pairs block which; combined in ray order (deterministic).
    std::vector<std::vector<std::pair<std::size_t, std::size_t>>> found(grid.num_rays());
    parallel_for(0, grid.num_rays(), [&](std::size_t r) {
      const std::vector<Extent> ext = grid.extents(r);
      for (const Extent& a : ext)
        for (const Extent& b : ext)
          if (a.block != b.block && b.highest_mid > a.lowest_mid) found[r].push_back({a.block, b.block});
    }, 64);
    for (const auto& pairs : found)
      for (const auto& [a, b] : pairs) {
        rel.blocked[2 * k][a * n + b] = true;      // b beyond a along +k: a cannot leave along +k
        rel.blocked[2 * k + 1][b * n + a] = true;  // and b cannot leave along -k
      }
  }
  return rel;
}

GluingPlan plan_gluing_order(const std::vector<Mesh>& blocks, const GluingOptions& options) {
  const std::size_t n = blocks.size();
  const BlockingRelation rel = compute_blocking(blocks, options);
  GluingPlan plan;
  plan.ray_spacing = rel.ray_spacing;
  std::vector<std::size_t> by_volume(n);
  std::iota(by_volume.begin(), by_volume.end(), 0);
  if (options.volumes.size() == n)
    std::stable_sort(by_volume.begin(), by_volume.end(),
                     [&](std::size_t a, std::size_t b) { return options.volumes[a] < options.volumes[b]; });
  std::vector<bool> present(n, true);
  std::vector<GluingStep> removed;
  for (bool progress = true; progress && removed.size() < n;) {
    progress = false;
    for (std::size_t b : by_volume) {
      if (!present[b]) continue;
      std::vector<int> directions;
      if (b < options.preferred_axis.size() && options.preferred_axis[b] >= 0) directions.push_back(options.preferred_axis[b]);
      for (int d : {4, 5, 0, 1, 2, 3})
        if (directions.empty() || d != directions.front()) directions.push_back(d);
      for (int d : directions) {
        bool free = true;
        for (std::size_t c = 0; c < n && free; ++c)
          if (present[c] && c != b && rel(d, b, c)) free = false;
        if (free) {
          removed.push_back({b, d});
          present[b] = false;
          progress = true;
          break;
        }
      }
      if (progress) break;
    }
  }
  for (std::size_t b = 0; b < n; ++b)
    if (present[b]) {
      plan.stuck.push_back(b);
      plan.steps.push_back({b, -1});
    }
  for (auto it = removed.rbegin(); it != removed.rend(); ++it) plan.steps.push_back(*it);
  if (plan.stuck.empty() && !plan.steps.empty()) plan.steps.front().axis = -1;  // the first block goes anywhere
  return plan;
}

}  // namespace subfab
