// SPDX-License-Identifier: GPL-3.0-or-later
#include "validate/box_separation.h"

#include <algorithm>
#include <cmath>

namespace subfab::detail {

FramedBlock::FramedBlock(const Mesh& block, const Eigen::Matrix3d& frame) : frame_(frame) {
  const bool identity = frame == Eigen::Matrix3d::Identity();
  Mesh rotated = block;
  box_.min = Vec3::Constant(std::numeric_limits<double>::infinity());
  box_.max = -box_.min;
  double largest_input = 0.0;
  for (Vec3& v : rotated.vertices) {
    largest_input = std::max(largest_input, v.cwiseAbs().maxCoeff());
    if (!identity) v = frame * v;
    box_.min = box_.min.cwiseMin(v);
    box_.max = box_.max.cwiseMax(v);
    largest_ = std::max(largest_, v.cwiseAbs().maxCoeff());
  }
  // |fl(u.v) - u.v| <= 3.4e-16 sum |u_i||v_i| (as overlap_volume_bound()); 0 for the identity.
  double row_sum = 0.0;
  for (int k = 0; k < 3; ++k) row_sum = std::max(row_sum, frame.row(k).cwiseAbs().sum());
  rounding_ = identity ? 0.0 : 4e-16 * row_sum * largest_input;
  index_ = std::make_unique<SolidIndex>(rotated);
}

double box_separation_bound(const FramedBlock& a, const FramedBlock& b) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (a.frame() != b.frame() || a.index().num_faces() == 0 || b.index().num_faces() == 0) return kInf;
  const Eigen::Matrix3d& frame = a.frame();
  if ((frame.transpose() * frame - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9) return kInf;
  // X contains the exact F a; Y = X shrunk by the margin (0 in the input frame).
  const double margin = a.rounding() == 0.0 && b.rounding() == 0.0 ? 0.0 : 1e-13 * std::max(a.largest(), b.largest());
  Box3 x = a.box();
  x.min.array() -= a.rounding();
  x.max.array() += a.rounding();
  Box3 y = x;
  y.min.array() += margin;
  y.max.array() -= margin;
  if (!(y.min.array() < y.max.array()).all()) return kInf;
  // Round Y inward so that the doubles are inside the shrunk box (the
  // additions above rounded to nearest).
  for (int k = 0; k < 3; ++k) {
    y.min[k] = std::nextafter(y.min[k], kInf);
    y.max[k] = std::nextafter(y.max[k], -kInf);
  }
  if (!(y.min.array() < y.max.array()).all()) return kInf;
  if (b.index().any_face_meets_open_box(y)) return kInf;
  if (b.index().is_inside(0.5 * (y.min + y.max))) return kInf;
  // vol(a ∩ b) <= vol(X \ Y'), Y' = Y shrunk by b's rounding; in frame units, / det F.
  const Vec3 outer = x.size(), inner = (y.size().array() - 2.0 * b.rounding()).max(0.0).matrix();
  // The centre's side of b carries over to the exact F b when b's surface
  // (within its rounding of the rounded one) stays farther from it than that.
  if (!(inner.minCoeff() > 2.0 * b.rounding())) return kInf;
  const double shell = (outer.prod() * (1.0 + 1e-15)) - inner.prod() * (1.0 - 1e-15);
  if (shell <= 0.0) return 0.0;
  return shell / (std::abs(frame.determinant()) * (1.0 - 1e-12));
}

}  // namespace subfab::detail
