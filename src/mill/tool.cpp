// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mill/tool.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "subfab/core/error.h"

namespace subfab {

Tool parse_tool(const std::string& text) {
  const auto colon = text.find(':');
  const std::string kind = colon == std::string::npos ? text : text.substr(0, colon);
  Tool tool;
  if (kind == "ball") {
    tool.shape = ToolShape::Ball;
  } else if (kind == "flat") {
    tool.shape = ToolShape::Flat;
  } else {
    throw InvalidArgumentError("tool '" + text + "': expected ball:D or flat:D (D the diameter in mm, e.g. ball:6)");
  }
  if (colon == std::string::npos)
    throw InvalidArgumentError("tool '" + text + "': the diameter is missing (e.g. " + kind + ":6)");
  const std::string number = text.substr(colon + 1);
  std::size_t used = 0;
  double d = 0.0;
  try {
    d = std::stod(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != number.size() || !std::isfinite(d) || d <= 0.0)
    throw InvalidArgumentError("tool '" + text + "': the diameter must be a positive number of mm (e.g. " + kind +
                               ":6)");
  tool.diameter = d;
  return tool;
}

std::string tool_description(const Tool& tool) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s end mill D%.3f mm", tool.shape == ToolShape::Ball ? "ball" : "flat",
                tool.diameter);
  return buf;
}

std::string tool_spec(const Tool& tool) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s:%g", tool.shape == ToolShape::Ball ? "ball" : "flat", tool.diameter);
  return buf;
}

double tool_profile(const Tool& tool, double d) {
  if (tool.shape == ToolShape::Flat) return 0.0;
  const double r = tool.radius();
  return r - std::sqrt(std::max(0.0, r * r - d * d));
}

}  // namespace subfab
