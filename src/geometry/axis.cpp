// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/geometry/axis.h"

#include <cmath>
#include <numbers>
#include <string>

#include "subfab/core/error.h"

namespace subfab {

Vec3 axis_direction(Axis a) {
  Vec3 d = Vec3::Zero();
  d[axis_dimension(a)] = axis_sign(a);
  return d;
}

std::string_view axis_name(Axis a) {
  static constexpr std::array<std::string_view, 6> kNames = {"+x", "-x", "+y", "-y", "+z", "-z"};
  return kNames[static_cast<std::size_t>(axis_index(a))];
}

std::optional<Axis> parse_axis(std::string_view name) {
  if (name.size() != 2) return std::nullopt;
  const char sign = name[0];
  const char letter = static_cast<char>(name[1] | 0x20);  // lower case
  if ((sign != '+' && sign != '-') || letter < 'x' || letter > 'z') return std::nullopt;
  return static_cast<Axis>(2 * (letter - 'x') + (sign == '-' ? 1 : 0));
}

Axis closest_axis(const Vec3& n) {
  Axis best = Axis::PosX;
  double best_dot = -std::numeric_limits<double>::infinity();
  for (Axis a : kAllAxes) {
    const double dot = axis_sign(a) * n[axis_dimension(a)];
    if (dot > best_dot) {
      best_dot = dot;
      best = a;
    }
  }
  return best;
}

double overhang_sine(double max_overhang_deg) {
  if (!(max_overhang_deg >= 0.0 && max_overhang_deg <= kMaxOverhangAllowanceDeg))
    throw InvalidArgumentError("--max-overhang must be between 0 and " +
                               std::to_string(static_cast<int>(kMaxOverhangAllowanceDeg)) +
                               " degrees (0 = exact height fields), got " + std::to_string(max_overhang_deg));
  if (max_overhang_deg == 0.0) return 0.0;
  return std::sin(max_overhang_deg * std::numbers::pi / 180.0);
}

}  // namespace subfab
