// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mill/read_gcode.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>

#include "subfab/core/error.h"

namespace subfab {

GcodeRead read_gcode(const std::string& text, const std::string& name) {
  GcodeRead out;
  std::optional<double> pos[3];
  int motion = -1, tool = 0;
  double feed = 0.0;
  bool spindle = false;
  std::istringstream in(text);
  std::string raw;
  int lineno = 0;
  while (std::getline(in, raw)) {
    ++lineno;
    auto fail = [&](const std::string& what) {
      throw IoError(name + ": line " + std::to_string(lineno) + ": " + what);
    };
    std::string line;  // without comments and spaces, upper case
    int depth = 0;
    for (char c : raw) {
      if (c == '(') {
        if (depth++) fail("nested comment");
      } else if (c == ')') {
        if (!depth--) fail("')' without '('");
      } else if (c == ';' && !depth) {
        break;
      } else if (!depth && c != ' ' && c != '\t' && c != '\r') {
        line.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
      }
    }
    if (depth) fail("unclosed comment");
    if (line.empty() || line == "%") continue;
    std::optional<double> target[3];
    bool moved = false;
    for (std::size_t i = 0; i < line.size();) {
      const char letter = line[i++];
      // The number: an optional sign, digits, at most one point (no
      // exponent, no hex: strtod alone would read "0X6" as a number).
      std::size_t j = i;
      if (j < line.size() && (line[j] == '+' || line[j] == '-')) ++j;
      std::size_t digits = 0, points = 0;
      while (j < line.size() && (std::isdigit(static_cast<unsigned char>(line[j])) || line[j] == '.')) {
        (line[j] == '.' ? points : digits) += 1;
        ++j;
      }
      const std::string word = std::string(1, letter) + line.substr(i, j - i);
      if (digits == 0 || points > 1) fail("word '" + word + "' without a valid number");
      const double value = std::strtod(line.substr(i, j - i).c_str(), nullptr);
      i = j;
      switch (letter) {
        case 'G':
          if (value == 0 || value == 1) {
            motion = static_cast<int>(value);
          } else if (value != 17 && value != 21 && value != 90 && value != 94) {
            fail("unsupported word " + word + " (expected G0 G1 G17 G21 G90 G94)");
          }
          break;
        case 'X': target[0] = value; moved = true; break;
        case 'Y': target[1] = value; moved = true; break;
        case 'Z': target[2] = value; moved = true; break;
        case 'F':
          if (!(value > 0)) fail("feed " + word + " must be positive");
          feed = value;
          break;
        case 'S':
          if (value < 0) fail("negative spindle speed " + word);
          break;
        case 'M':
          if (value == 3) {
            spindle = true;
          } else if (value == 5) {
            spindle = false;
          } else if (value == 0) {
            ++tool;
            ++out.num_tool_changes;
          } else if (value == 2 || value == 30) {
            out.ended = true;
          } else if (value != 8 && value != 9) {
            fail("unsupported word " + word + " (expected M0 M2 M3 M5 M8 M9 M30)");
          }
          break;
        default: fail("unsupported word " + word);
      }
    }
    if (!moved) continue;
    if (motion < 0) fail("coordinates without G0 or G1");
    if (motion == 1 && !(feed > 0)) fail("G1 without a feed (F)");
    if (motion == 1 && !spindle) out.spindle_on_for_every_cut = false;
    const bool known = pos[0] && pos[1] && pos[2];
    Vec3 from = known ? Vec3(*pos[0], *pos[1], *pos[2]) : Vec3::Zero();
    for (int a = 0; a < 3; ++a)
      if (target[a]) pos[a] = target[a];
    if (known && pos[0] && pos[1] && pos[2])
      out.moves.push_back({motion == 0, from, Vec3(*pos[0], *pos[1], *pos[2]), feed, tool, lineno});
  }
  out.num_lines = lineno;
  return out;
}

}  // namespace subfab
