// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mill/check_milling.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "subfab/core/parallel.h"

namespace subfab {

HeightMap target_heights(const Mesh& block, const HeightMap& like, std::vector<unsigned char>& footprint) {
  HeightMap t = like;
  std::fill(t.z.begin(), t.z.end(), 0.0);
  footprint.assign(t.z.size(), 0);
  const double res = t.resolution;
  for (const Triangle& f : block.faces) {
    const Vec3 &a = block.vertices[f[0]], &b = block.vertices[f[1]], &c = block.vertices[f[2]];
    const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    if (!(area > 0.0)) continue;  // only triangles facing up (counter-clockwise seen from +z)
    const int i0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}) / res - 0.5)));
    const int i1 = std::min(t.nx - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}) / res - 0.5)));
    const int j0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}) / res - 0.5)));
    const int j1 = std::min(t.ny - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}) / res - 0.5)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double x = t.x(i), y = t.y(j);
        // Barycentric coordinates in xy (boundary included).
        const double l0 = ((b.x() - x) * (c.y() - y) - (b.y() - y) * (c.x() - x)) / area;
        const double l1 = ((c.x() - x) * (a.y() - y) - (c.y() - y) * (a.x() - x)) / area;
        const double l2 = 1.0 - l0 - l1;
        if (l0 < -1e-12 || l1 < -1e-12 || l2 < -1e-12) continue;
        const double z = l0 * a.z() + l1 * b.z() + l2 * c.z();
        const std::size_t k = static_cast<std::size_t>(j) * t.nx + i;
        if (!footprint[k] || z > t.z[k]) t.z[k] = z;
        footprint[k] = 1;
      }
  }
  return t;
}

HeightMap ideal_surface(const TriangleGrid& grid, const Tool& tool, const HeightMap& like) {
  HeightMap cl = like;
  parallel_for(0, static_cast<std::size_t>(cl.ny), [&](std::size_t j) {
    for (int i = 0; i < cl.nx; ++i) cl.at(i, static_cast<int>(j)) = drop_cutter(grid, tool, cl.x(i), cl.y(static_cast<int>(j)));
  });
  // Opening: M(c) = min over positions p within the tool radius of CL(p) + profile(|p - c|).
  const double res = like.resolution, r = tool.radius();
  const int reach = static_cast<int>(std::floor(r / res));
  struct Offset {
    int di, dj;
    double lift;
  };
  std::vector<Offset> kernel;
  for (int dj = -reach; dj <= reach; ++dj)
    for (int di = -reach; di <= reach; ++di) {
      const double d = res * std::hypot(di, dj);
      if (d <= r) kernel.push_back({di, dj, tool_profile(tool, d)});
    }
  HeightMap m = like;
  parallel_for(0, static_cast<std::size_t>(m.ny), [&](std::size_t jj) {
    const int j = static_cast<int>(jj);
    for (int i = 0; i < m.nx; ++i) {
      double best = std::numeric_limits<double>::infinity();
      for (const Offset& o : kernel) {
        const int pi = i + o.di, pj = j + o.dj;
        if (pi < 0 || pj < 0 || pi >= m.nx || pj >= m.ny) continue;
        best = std::min(best, cl.at(pi, pj) + o.lift);
      }
      m.at(i, j) = best;
    }
  });
  return m;
}

MillCheck check_milling(const HeightMap& milled, const HeightMap& target, const std::vector<unsigned char>& footprint,
                        const HeightMap& ideal, const MillCheckOptions& options) {
  MillCheck c;
  c.resolution = milled.resolution;
  c.num_cells = milled.z.size();
  const double cell_area = milled.resolution * milled.resolution;
  double sum = 0.0;
  std::size_t reached = 0;
  for (std::size_t k = 0; k < milled.z.size(); ++k) {
    const double t = target.z[k];
    c.max_gouge = std::max(c.max_gouge, t - milled.z[k]);
    const double left = ideal.z[k] - t;
    const bool unreachable = left > options.unreachable_tolerance;
    if (!footprint[k]) {
      if (unreachable) c.foot_area += cell_area;
      continue;
    }
    c.footprint_area += cell_area;
    if (unreachable) {
      c.unreachable_area += cell_area;
      c.unreachable_max = std::max(c.unreachable_max, left);
      continue;
    }
    const double residual = std::max(0.0, milled.z[k] - t);
    c.max_residual = std::max(c.max_residual, residual);
    sum += residual;
    ++reached;
  }
  c.mean_residual = reached ? sum / static_cast<double>(reached) : 0.0;
  return c;
}

}  // namespace subfab
