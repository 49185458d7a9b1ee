// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mill/toolpath.h"

#include "mill/path_builder.h"

namespace subfab {

PathLengths path_lengths(const Toolpath& path) {
  PathLengths out;
  Vec3 at(0.0, 0.0, path.safe_z);
  for (const Move& m : path.moves) {
    const double d = (m.to - at).norm();
    (m.kind == MoveKind::Rapid ? out.rapid : m.kind == MoveKind::Plunge ? out.plunge : out.cut) += d;
    at = m.to;
  }
  return out;
}

double machining_time(const PathLengths& lengths, const Feeds& feeds) {
  return 60.0 * (lengths.cut / feeds.feed + lengths.plunge / feeds.plunge + lengths.rapid / feeds.rapid);
}

namespace detail {

double round_mm(double x) {
  const double r = std::round(x * 1000.0) / 1000.0;
  return r == 0.0 ? 0.0 : r;  // no -0
}

double ceil_mm(double z) {
  const double r = std::ceil(z * 1000.0 - 1e-7) / 1000.0;
  return r == 0.0 ? 0.0 : r;
}

std::vector<double> spaced(double length, double spacing) {
  const int n = std::max(1, static_cast<int>(std::ceil(length / spacing - 1e-9)) + 1);
  std::vector<double> out(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) out[static_cast<std::size_t>(i)] = n == 1 ? 0.0 : round_mm(length * i / (n - 1));
  return out;
}

namespace {
//! Distance from p to the segment a-b.
double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 u = b - a;
  const double l2 = u.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp((p - a).dot(u) / l2, 0.0, 1.0) : 0.0;
  return (a + t * u - p).norm();
}
}  // namespace

void PathBuilder::add(MoveKind kind, const Vec3& to) {
  if (to == at_) return;  // no zero-length moves
  if (!moves_.empty() && moves_.back().kind == kind && merged_.size() < 4096) {
    // Drop the last move's end point if every point dropped since the
    // anchor stays within tolerance_ of the longer chord, going forward.
    const Vec3& end = moves_.back().to;
    const bool forward = (end - anchor_).dot(to - end) > 0.0;
    bool ok = forward && segment_distance(end, anchor_, to) <= tolerance_;
    for (std::size_t i = 0; ok && i < merged_.size(); ++i) ok = segment_distance(merged_[i], anchor_, to) <= tolerance_;
    if (ok) {
      merged_.push_back(end);
      moves_.back().to = to;
      at_ = to;
      return;
    }
  }
  anchor_ = at_;
  merged_.clear();
  moves_.push_back({kind, to});
  at_ = to;
}

}  // namespace detail
}  // namespace subfab
