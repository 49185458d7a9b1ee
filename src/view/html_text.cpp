// SPDX-License-Identifier: GPL-3.0-or-later
#include "view/html_text.h"

#include <cmath>
#include <cstdio>

namespace subfab::detail {

std::string escape_html(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string format_number(double value, int digits) {
  char buf[64];
  if (std::abs(value) >= std::pow(10.0, digits) && std::abs(value) < 1e15)
    std::snprintf(buf, sizeof buf, "%.0f", value);  // 76290, not 7.629e+04
  else
    std::snprintf(buf, sizeof buf, "%.*g", digits, value);
  return buf;
}

}  // namespace subfab::detail
