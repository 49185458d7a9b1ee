// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mill/machining_time.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "subfab/core/error.h"

namespace subfab {
namespace {

//! Time (s) to cover `length` starting at speed v0 and ending at v1 (both
//! reachable: |v1^2 - v0^2| <= 2 a length), cruising at most at v.
double trapezoid(double length, double v0, double v1, double v, double a) {
  if (!std::isfinite(a)) return length / v;
  const double peak2 = a * length + 0.5 * (v0 * v0 + v1 * v1);  // speed^2 where accelerating and braking meet
  if (peak2 <= v * v) {
    const double peak = std::sqrt(peak2);
    return (2.0 * peak - v0 - v1) / a;
  }
  const double ramps = (2.0 * v * v - v0 * v0 - v1 * v1) / (2.0 * a);  // distance spent accelerating and braking
  return (2.0 * v - v0 - v1) / a + (length - ramps) / v;
}

}  // namespace

double machining_time(const Toolpath& path, const Feeds& feeds, const MotionLimits& limits) {
  if (!(limits.accel > 0.0) || !(limits.junction_deviation > 0.0))
    throw InvalidArgumentError("--accel and the junction deviation must be positive");
  const double a = limits.accel;
  struct Segment {
    double length;
    Vec3 dir;
    double speed;  // mm/s
  };
  std::vector<Segment> segs;
  Vec3 at(0.0, 0.0, path.safe_z);
  for (const Move& m : path.moves) {
    const Vec3 d = m.to - at;
    at = m.to;
    const double len = d.norm();
    if (len <= 0.0) continue;
    const double feed = m.kind == MoveKind::Rapid ? feeds.rapid : m.kind == MoveKind::Plunge ? feeds.plunge : feeds.feed;
    segs.push_back({len, d / len, feed / 60.0});
  }
  const std::size_t n = segs.size();
  if (n == 0) return 0.0;
  // entry[i]: speed at the start of segment i; entry[n] = 0 (stop at the end).
  std::vector<double> entry(n + 1, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    // GRBL: v^2 = a delta sin(theta/2) / (1 - sin(theta/2)), theta the angle between
    // the reversed incoming direction and the outgoing one (pi: straight on).
    const double cos_theta = -segs[i - 1].dir.dot(segs[i].dir);
    double limit = std::min(segs[i - 1].speed, segs[i].speed);
    if (cos_theta > -0.999999) {
      const double sin_half = std::sqrt(std::max(0.0, 0.5 * (1.0 - cos_theta)));
      limit = cos_theta >= 0.999999 ? 0.0 : std::min(limit, std::sqrt(a * limits.junction_deviation * sin_half / (1.0 - sin_half)));
    }
    entry[i] = limit;
  }
  for (std::size_t i = n; i-- > 0;)  // backward: able to brake to the next entry speed
    entry[i] = std::min(entry[i], std::sqrt(entry[i + 1] * entry[i + 1] + 2.0 * a * segs[i].length));
  for (std::size_t i = 0; i < n; ++i)  // forward: able to reach it
    entry[i + 1] = std::min(entry[i + 1], std::sqrt(entry[i] * entry[i] + 2.0 * a * segs[i].length));
  double time = 0.0;
  for (std::size_t i = 0; i < n; ++i) time += trapezoid(segs[i].length, entry[i], entry[i + 1], segs[i].speed, a);
  return time;
}

}  // namespace subfab
