// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/validate/block_thickness.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace subfab {

BlockThickness block_thickness(const Mesh& block, const Eigen::Matrix3d& frame) {
  BlockThickness r;
  const double volume = signed_volume(block);
  // sum_f |u.N_f| with N_f = (b - a) x (c - a) = 2 A_f n_f, per row u.
  std::array<double, 3> crossed{};
  for (std::size_t f = 0; f < block.num_faces(); ++f) {
    const Vec3 n = face_normal_scaled(block, f);
    for (int k = 0; k < 3; ++k) crossed[static_cast<std::size_t>(k)] += std::abs(frame.row(k).dot(n));
  }
  r.thickness = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const std::size_t ks = static_cast<std::size_t>(k);
    // 2 V / sum |u.n| A = 4 V / sum |u.N|
    r.along[ks] = volume > 0 && crossed[ks] > 0 ? 4.0 * volume / crossed[ks] : 0.0;
    if (r.along[ks] < r.thickness) {
      r.thickness = r.along[ks];
      r.thinnest_row = k;
    }
  }
  r.axis = frame.row(r.thinnest_row).transpose().normalized();
  return r;
}

}  // namespace subfab
