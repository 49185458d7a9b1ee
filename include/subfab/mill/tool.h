// SPDX-License-Identifier: GPL-3.0-or-later
//! \file tool.h
//! The milling tools of `subfab mill`: a ball-end or a flat-end mill, held
//! vertically (3-axis machine). The tool's reference point (its "cutter
//! location", what G-code positions) is the lowest point of the tool: the
//! tip of a ball end, the centre of a flat end's bottom disk.
#pragma once

#include <string>

namespace subfab {

enum class ToolShape { Ball, Flat };

//! A vertical end mill. All lengths in millimetres.
struct Tool {
  ToolShape shape = ToolShape::Ball;
  double diameter = 6.0;  // mm, > 0

  double radius() const { return 0.5 * diameter; }
};

//! Parses "ball:D" or "flat:D" (D the diameter in mm, positive and finite).
//! \throw InvalidArgumentError on any other text, naming what is expected.
Tool parse_tool(const std::string& text);

//! "ball end mill D6.000 mm" / "flat end mill D8.000 mm" (used in G-code comments).
std::string tool_description(const Tool& tool);

//! "ball:6" / "flat:8" (the syntax of parse_tool, for reports).
std::string tool_spec(const Tool& tool);

//! Height of the tool's lower surface above its reference point at horizontal
//! distance d from its axis (0 <= d <= radius): R - sqrt(R^2 - d^2) for a
//! ball end, 0 for a flat end.
double tool_profile(const Tool& tool, double d);

}  // namespace subfab
