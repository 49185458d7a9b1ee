// SPDX-License-Identifier: GPL-3.0-or-later
// machining_time() with acceleration against hand-computed trapezoids.
#include "subfab/mill/machining_time.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "subfab/core/error.h"

namespace subfab {
namespace {

Toolpath path_of(std::initializer_list<Vec3> points, MoveKind kind = MoveKind::Cut) {
  Toolpath p;
  p.safe_z = 0.0;
  for (const Vec3& q : points) p.moves.push_back({kind, q});
  return p;
}

TEST(MachiningTime, StraightMoveIsATrapezoid) {
  const Feeds feeds{1200.0, 300.0, 3000.0};  // 20 mm/s cutting
  const MotionLimits limits{400.0, 0.01};
  // 100 mm from rest to rest: 0.05 s and 0.5 mm to reach 20 mm/s, same to stop.
  const Toolpath one = path_of({{100, 0, 0}});
  EXPECT_NEAR(machining_time(one, feeds, limits), 2 * 0.05 + 99.0 / 20.0, 1e-9);
  // The same line in 100 collinear pieces: no slowing down in between.
  Toolpath pieces;
  for (int i = 1; i <= 100; ++i) pieces.moves.push_back({MoveKind::Cut, Vec3(i, 0, 0)});
  EXPECT_NEAR(machining_time(pieces, feeds, limits), machining_time(one, feeds, limits), 1e-9);
  // Too short to cruise: 0.5 mm accelerating and braking, peak sqrt(a L) = sqrt(200).
  EXPECT_NEAR(machining_time(path_of({{0.5, 0, 0}}), feeds, limits), 2 * std::sqrt(200.0) / 400.0, 1e-9);
  // Infinite acceleration: the lengths over the feeds.
  const MotionLimits instant{std::numeric_limits<double>::infinity(), 0.01};
  EXPECT_NEAR(machining_time(one, feeds, instant), machining_time(path_lengths(one), feeds), 1e-9);
  EXPECT_THROW(machining_time(one, feeds, MotionLimits{0.0, 0.01}), InvalidArgumentError);
}

TEST(MachiningTime, CornersSlowDownAsGrblDoes) {
  const Feeds feeds{1200.0, 300.0, 3000.0};
  const MotionLimits limits{400.0, 0.01};
  // A right angle: junction speed^2 = a delta sin45 / (1 - sin45).
  const double s = std::sqrt(0.5), vj = std::sqrt(400.0 * 0.01 * s / (1.0 - s));
  const double leg = 0.05 + (20.0 - vj) / 400.0 + (10.0 - (400.0 - vj * vj) / 800.0 - 0.5) / 20.0;
  EXPECT_NEAR(machining_time(path_of({{10, 0, 0}, {10, 10, 0}}), feeds, limits), 2 * leg, 1e-9);
  // A reversal stops the tool: two separate trapezoids.
  EXPECT_NEAR(machining_time(path_of({{10, 0, 0}, {0, 0, 0}}), feeds, limits),
              2 * machining_time(path_of({{10, 0, 0}}), feeds, limits), 1e-9);
  // A zig-zag of short moves is slower than its lengths over the feed.
  Toolpath zig;
  for (int i = 1; i <= 50; ++i) zig.moves.push_back({MoveKind::Cut, Vec3(i * 0.5, (i % 2) * 0.5, 0)});
  EXPECT_GT(machining_time(zig, feeds, limits), 1.5 * machining_time(path_lengths(zig), feeds));
}

}  // namespace
}  // namespace subfab
