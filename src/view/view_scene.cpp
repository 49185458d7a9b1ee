// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/view/view_scene.h"

#include <cstdio>

namespace subfab {

Rgb direction_color(const std::string& axis) {
  if (axis == "+x") return {215, 48, 48};    // red
  if (axis == "-x") return {40, 190, 190};   // cyan
  if (axis == "+y") return {60, 180, 60};    // green
  if (axis == "-y") return {190, 60, 190};   // magenta
  if (axis == "+z") return {60, 60, 225};    // blue
  if (axis == "-z") return {205, 205, 45};   // yellow
  return {150, 150, 150};
}

std::string to_hex(const Rgb& color) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", color[0] & 255, color[1] & 255, color[2] & 255);
  return buf;
}

}  // namespace subfab
