// SPDX-License-Identifier: GPL-3.0-or-later
#include "unfold/fidelity_band.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "subfab/core/error.h"

namespace subfab::unfold_detail {
namespace {

struct EdgeSetHash {
  std::size_t operator()(const std::vector<std::uint64_t>& v) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint64_t e : v) h = (h ^ e) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

}  // namespace

FidelityBand::FidelityBand(const Mesh& reference, const GridPoints& grid, const std::vector<std::uint8_t>& inside,
                           double radius) {
  if (!(radius > 0) || !std::isfinite(radius)) throw InvalidArgumentError("fidelity radius must be > 0 grid spacings");
  const std::size_t nx = static_cast<std::size_t>(grid.size[0]), ny = static_cast<std::size_t>(grid.size[1]);
  stride_ = {1, nx, nx * ny};
  const double h = grid.spacing;
  const double r2 = radius * radius;
  std::unordered_map<std::vector<std::uint64_t>, std::uint32_t, EdgeSetHash> ids;
  offsets_.push_back(0);
  std::vector<std::uint64_t> set;
  auto add_sample = [&](const Vec3& x) {
    const Vec3 u = (x - grid.origin) / h;  // lattice coordinates
    std::array<int, 3> lo{}, hi{};
    for (int a = 0; a < 3; ++a) {
      lo[static_cast<std::size_t>(a)] = std::max(0, static_cast<int>(std::ceil(u[a] - radius)));
      hi[static_cast<std::size_t>(a)] = std::min(grid.size[static_cast<std::size_t>(a)] - 1,
                                                 static_cast<int>(std::floor(u[a] + radius)));
    }
    auto in_ball = [&](int i, int j, int k) {
      const double dx = i - u[0], dy = j - u[1], dz = k - u[2];
      return dx * dx + dy * dy + dz * dz <= r2;
    };
    set.clear();
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) {
          if (!in_ball(i, j, k)) continue;
          const std::uint64_t p = grid.index(i, j, k);
          if (i < hi[0] && in_ball(i + 1, j, k)) set.push_back(3 * p + 0);
          if (j < hi[1] && in_ball(i, j + 1, k)) set.push_back(3 * p + 1);
          if (k < hi[2] && in_ball(i, j, k + 1)) set.push_back(3 * p + 2);
        }
    if (set.empty()) return;  // std::sort not needed: enumeration order is ascending in p
    if (ids.emplace(set, static_cast<std::uint32_t>(offsets_.size() - 1)).second) {
      edges_.insert(edges_.end(), set.begin(), set.end());
      offsets_.push_back(edges_.size());
    }
  };
  // Samples: a barycentric grid on every triangle, finer than half a spacing.
  for (const auto& f : reference.faces) {
    const Vec3 &a = reference.vertices[static_cast<std::size_t>(f[0])], &b = reference.vertices[static_cast<std::size_t>(f[1])],
               &c = reference.vertices[static_cast<std::size_t>(f[2])];
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const double steps = std::ceil(longest / (0.5 * h));
    const int n = !(steps > 1) ? 1 : (steps > 256 ? 256 : static_cast<int>(steps));
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) add_sample(a + (double(i) / n) * (b - a) + (double(j) / n) * (c - a));
  }
  const std::size_t num = num_constraints();
  changes_.resize(num);
  for (std::size_t c = 0; c < num; ++c) changes_[c] = count_changes(inside, c);
  // Point -> constraints (CSR), each constraint listed once per point.
  std::vector<std::pair<std::size_t, std::uint32_t>> pairs;
  for (std::size_t c = 0; c < num; ++c) {
    const std::size_t first = pairs.size();
    for (std::size_t e = offsets_[c]; e < offsets_[c + 1]; ++e) {
      const std::size_t p = static_cast<std::size_t>(edges_[e] / 3);
      pairs.push_back({p, static_cast<std::uint32_t>(c)});
      pairs.push_back({p + stride_[static_cast<std::size_t>(edges_[e] % 3)], static_cast<std::uint32_t>(c)});
    }
    std::sort(pairs.begin() + static_cast<std::ptrdiff_t>(first), pairs.end());
    pairs.erase(std::unique(pairs.begin() + static_cast<std::ptrdiff_t>(first), pairs.end()), pairs.end());
  }
  std::sort(pairs.begin(), pairs.end());
  point_offsets_.assign(grid.num_points() + 1, 0);
  for (const auto& pc : pairs) ++point_offsets_[pc.first + 1];
  for (std::size_t p = 0; p < grid.num_points(); ++p) point_offsets_[p + 1] += point_offsets_[p];
  by_point_.reserve(pairs.size());
  for (const auto& pc : pairs) by_point_.push_back(pc.second);
}

int FidelityBand::count_changes(const std::vector<std::uint8_t>& inside, std::size_t c) const {
  int n = 0;
  for (std::size_t e = offsets_[c]; e < offsets_[c + 1]; ++e) {
    const std::size_t p = static_cast<std::size_t>(edges_[e] / 3);
    n += inside[p] != inside[p + stride_[static_cast<std::size_t>(edges_[e] % 3)]];
  }
  return n;
}

std::vector<std::uint32_t> FidelityBand::touched(const std::vector<std::size_t>& flipped) const {
  std::vector<std::uint32_t> out;
  if (point_offsets_.empty()) return out;
  for (std::size_t p : flipped) out.insert(out.end(), by_point_.begin() + static_cast<std::ptrdiff_t>(point_offsets_[p]),
                                           by_point_.begin() + static_cast<std::ptrdiff_t>(point_offsets_[p + 1]));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool FidelityBand::allows(const std::vector<std::uint8_t>& inside, const std::vector<std::size_t>& flipped) const {
  for (std::uint32_t c : touched(flipped))
    if (changes_[c] > 0 && count_changes(inside, c) == 0) return false;
  return true;
}

void FidelityBand::commit(const std::vector<std::uint8_t>& inside, const std::vector<std::size_t>& flipped) {
  for (std::uint32_t c : touched(flipped)) changes_[c] = count_changes(inside, c);
}

}  // namespace subfab::unfold_detail
