// SPDX-License-Identifier: GPL-3.0-or-later
//! \file rs274_words.h
//! A test-only RS-274 reader, written apart from the library's read_gcode():
//! it checks every word `subfab mill` emits against what GRBL 1.1 and
//! LinuxCNC both accept, and the program's structure. It returns the list of
//! problems (empty when the program is clean).
#pragma once

#include <cstdlib>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace subfab::test {

struct Rs274Bounds {
  double x = 1e9, y = 1e9, z = 1e9;  // every coordinate within [0, bound]
};

struct Rs274Summary {
  std::vector<std::string> problems;
  int num_code_lines = 0, num_g1 = 0, num_g0 = 0, num_pauses = 0;
  bool percent_wrapped = false;
  std::string last_code;  // the last line with code (e.g. "M30")
};

inline Rs274Summary check_rs274(const std::string& text, const Rs274Bounds& bounds) {
  Rs274Summary s;
  const std::set<std::string> g_ok = {"G0", "G1", "G17", "G21", "G90", "G94"};
  const std::set<std::string> m_ok = {"M0", "M2", "M3", "M5", "M8", "M9", "M30"};
  const std::regex decimal("^-?[0-9]+\\.[0-9]{3}$");
  std::istringstream in(text);
  std::string line;
  int n = 0;
  bool units = false, spindle = false, have_feed = false, ended = false;
  std::vector<std::string> lines;
  // Messages built by append (GCC 12 warns falsely on "literal" + std::string).
  auto problem = [&](const std::string& a, const char* b = "") {
    std::string msg = "line ";
    msg.append(std::to_string(n)).append(": ").append(a).append(b);
    s.problems.push_back(msg);
  };
  while (std::getline(in, line)) {
    ++n;
    lines.push_back(line);
    if (line.size() > 80) problem("longer than 80 characters");
    if (line == "%") continue;
    if (!line.empty() && line.front() == '(') {
      if (line.back() != ')' || line.find('(', 1) != std::string::npos || line.find(')') != line.size() - 1)
        problem("malformed comment");
      continue;
    }
    if (line.find('(') != std::string::npos || line.find(';') != std::string::npos) problem("comment after code");
    if (ended) problem("code after the program end");
    ++s.num_code_lines;
    s.last_code = line;
    std::istringstream words(line);
    std::string w;
    bool motion = false, g1 = false;
    while (words >> w) {
      const char letter = w[0];
      const std::string number = w.substr(1);
      if (letter == 'G' || letter == 'M') {
        const std::set<std::string>& ok = letter == 'G' ? g_ok : m_ok;
        if (!ok.count(w)) problem(w, " is not in the common GRBL/LinuxCNC subset");
        if (w == "G21") units = true;
        if (w == "G0" || w == "G1") {
          motion = true;
          g1 = w == "G1";
          (g1 ? s.num_g1 : s.num_g0)++;
          if (!units) problem("motion before G21");
        }
        if (w == "M3") spindle = true;
        if (w == "M5") spindle = false;
        if (w == "M0") {
          ++s.num_pauses;
          if (spindle) problem("pause with the spindle on");
        }
        if (w == "M2" || w == "M30") ended = true;
      } else if (letter == 'X' || letter == 'Y' || letter == 'Z' || letter == 'F' || letter == 'S') {
        if (!std::regex_match(number, decimal)) problem(w, ": the number is not -d.ddd");
        const double v = std::strtod(number.c_str(), nullptr);
        if (letter == 'X' && (v < 0 || v > bounds.x)) problem(w, " outside the stock");
        if (letter == 'Y' && (v < 0 || v > bounds.y)) problem(w, " outside the stock");
        if (letter == 'Z' && (v < 0 || v > bounds.z)) problem(w, " outside [0, safe height]");
        if (letter == 'F') have_feed = v > 0;
        if ((letter == 'X' || letter == 'Y' || letter == 'Z') && !motion) problem(w, " without G0 or G1 on its line");
      } else {
        problem(w, ": unexpected word");
      }
    }
    if (g1 && !have_feed) problem("G1 before any feed");
    if (g1 && !spindle) problem("G1 with the spindle off");
  }
  if (!ended) s.problems.push_back("no program end (M2 or M30)");
  s.percent_wrapped = !lines.empty() && lines.front() == "%" && lines.back() == "%";
  return s;
}

}  // namespace subfab::test
