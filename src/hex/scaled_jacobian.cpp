// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/scaled_jacobian.h"

#include <algorithm>

#include "subfab/core/parallel.h"

namespace subfab {

double scaled_jacobian(const std::array<Vec3, 8>& p) {
  double worst = 1.0;
  for (std::size_t i = 0; i < 8; ++i) {
    const auto& n = kHexCornerNeighbors[i];
    Vec3 e[3];
    for (std::size_t k = 0; k < 3; ++k) {
      e[k] = p[static_cast<std::size_t>(n[k])] - p[i];
      const double len = e[k].norm();
      if (!(len > 0)) return -1.0;
      e[k] /= len;
    }
    worst = std::min(worst, e[0].dot(e[1].cross(e[2])));
  }
  return worst;
}

double scaled_jacobian(const HexMesh& mesh, std::size_t h) {
  std::array<Vec3, 8> p;
  for (std::size_t k = 0; k < 8; ++k) p[k] = mesh.vertices[static_cast<std::size_t>(mesh.hexes[h][k])];
  return scaled_jacobian(p);
}

std::vector<double> scaled_jacobians(const HexMesh& mesh) {
  std::vector<double> out(mesh.hexes.size());
  parallel_for(0, mesh.hexes.size(), [&](std::size_t h) { out[h] = scaled_jacobian(mesh, h); }, 256);
  return out;
}

double min_scaled_jacobian(const std::vector<double>& sj) {
  return sj.empty() ? 1.0 : *std::min_element(sj.begin(), sj.end());
}

double mean_scaled_jacobian(const std::vector<double>& sj) {
  double s = 0;
  for (double x : sj) s += x;
  return sj.empty() ? 1.0 : s / static_cast<double>(sj.size());
}

}  // namespace subfab
