// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mill/draw_milling_map.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace subfab {
namespace {

using Rgb = std::array<double, 3>;

Rgb mix(const Rgb& a, const Rgb& b, double t) {
  t = std::clamp(t, 0.0, 1.0);
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

//! What a cell shows, in order of importance (a higher rank wins when cells
//! are merged into one pixel).
struct Cell {
  int rank = 0;  // 0 table, 1 foot, 2 reached, 3 unreachable, 4 gouge
  double residual = 0.0;
};

Cell classify(const HeightMap& milled, const HeightMap& target, const std::vector<unsigned char>& footprint,
              const HeightMap& ideal, const MillCheckOptions& options, std::size_t k) {
  const bool unreachable = ideal.z[k] - target.z[k] > options.unreachable_tolerance;
  if (target.z[k] - milled.z[k] > milled.resolution) return {4, 0.0};
  if (!footprint[k]) return {unreachable ? 1 : 0, 0.0};
  if (unreachable) return {3, 0.0};
  return {2, std::max(0.0, milled.z[k] - target.z[k])};
}

Rgb colour(const Cell& c) {
  static const Rgb table{225, 225, 225}, foot{205, 180, 135}, unreachable{205, 40, 205}, gouge{30, 60, 255};
  static const Rgb green{110, 195, 110}, yellow{235, 210, 60}, red{215, 45, 35};
  switch (c.rank) {
    case 0: return table;
    case 1: return foot;
    case 3: return unreachable;
    case 4: return gouge;
    default:
      if (c.residual <= 0.02) return green;
      if (c.residual <= 0.1) return mix(green, yellow, (c.residual - 0.02) / 0.08);
      return mix(yellow, red, (c.residual - 0.1) / 0.2);
  }
}

}  // namespace

RgbImage draw_milling_map(const HeightMap& milled, const HeightMap& target, const std::vector<unsigned char>& footprint,
                          const HeightMap& ideal, const MillCheckOptions& options, int max_side) {
  const int k = std::max(1, static_cast<int>(std::ceil(static_cast<double>(std::max(milled.nx, milled.ny)) /
                                                        std::max(1, max_side))));
  const int w = (milled.nx + k - 1) / k, h = (milled.ny + k - 1) / k;
  RgbImage img(w, h, 255);
  const double res = milled.resolution;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      Cell best{-1, 0.0};
      int bi = px * k, bj = py * k;
      for (int j = py * k; j < std::min(milled.ny, (py + 1) * k); ++j)
        for (int i = px * k; i < std::min(milled.nx, (px + 1) * k); ++i) {
          const Cell c = classify(milled, target, footprint, ideal, options,
                                  static_cast<std::size_t>(j) * milled.nx + i);
          if (c.rank > best.rank || (c.rank == best.rank && c.residual > best.residual)) {
            best = c;
            bi = i;
            bj = j;
          }
        }
      // Lambert shading of the block's surface (light from the upper left, above).
      const int i0 = std::max(bi - 1, 0), i1 = std::min(bi + 1, milled.nx - 1);
      const int j0 = std::max(bj - 1, 0), j1 = std::min(bj + 1, milled.ny - 1);
      const double gx = i1 > i0 ? (target.at(i1, bj) - target.at(i0, bj)) / ((i1 - i0) * res) : 0.0;
      const double gy = j1 > j0 ? (target.at(bi, j1) - target.at(bi, j0)) / ((j1 - j0) * res) : 0.0;
      const double lx = -0.5, ly = 0.5, lz = std::sqrt(0.5);
      const double lambert = std::max(0.0, (-gx * lx - gy * ly + lz) / std::sqrt(gx * gx + gy * gy + 1.0));
      const double shade = 0.55 + 0.45 * lambert;
      const Rgb c = colour(best);
      img.set(px, h - 1 - py, static_cast<std::uint8_t>(std::lround(c[0] * shade)),
              static_cast<std::uint8_t>(std::lround(c[1] * shade)), static_cast<std::uint8_t>(std::lround(c[2] * shade)));
    }
  return img;
}

}  // namespace subfab
