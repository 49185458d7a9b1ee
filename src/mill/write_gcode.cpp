// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mill/write_gcode.h"

#include <cmath>
#include <cstdio>

#include "subfab/core/error.h"

namespace subfab {
namespace {

//! A number with 3 decimals, never "-0.000".
std::string num(double x) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3f", x);
  std::string s = buf;
  if (s == "-0.000") s = "0.000";
  return s;
}

//! A comment line: parentheses and non-ASCII removed, at most 80 characters.
std::string comment(const std::string& text, bool message = false) {
  std::string clean;
  for (char c : text)
    if (c >= 32 && c < 127 && c != '(' && c != ')') clean.push_back(c);
  std::string line = message ? "(MSG, " + clean : "(" + clean;
  if (line.size() > 79) line.resize(79);
  return line + ")\n";
}

class Writer {
 public:
  explicit Writer(const GcodeOptions& o) : o_(o) {}

  void line(const std::string& s) { text_ += s + "\n"; }

  //! One move: only the axes that change, F when the feed changes.
  void move(const Move& m) {
    std::string s = m.kind == MoveKind::Rapid ? "G0" : "G1";
    const std::string x = num(m.to.x()), y = num(m.to.y()), z = num(m.to.z());
    if (x != x_) s += " X" + x;
    if (y != y_) s += " Y" + y;
    if (z != z_) s += " Z" + z;
    if (s.size() == 2) return;
    if (m.kind != MoveKind::Rapid) {
      const double f = m.kind == MoveKind::Plunge ? o_.feeds.plunge : o_.feeds.feed;
      const std::string fs = num(f);
      if (fs != f_) s += " F" + fs;
      f_ = fs;
    }
    x_ = x, y_ = y, z_ = z;
    line(s);
  }
  //! Forgets the position and goes straight up to z (the position is unknown
  //! at the start and after a tool change: X and Y are written again).
  void rapid_up(double z) {
    x_ = y_ = f_ = "";
    z_ = num(z);
    line("G0 Z" + z_);
  }

  std::string text_;

 private:
  const GcodeOptions& o_;
  std::string x_, y_, z_, f_;
};

}  // namespace

GcodeDialect parse_dialect(const std::string& name) {
  if (name == "grbl") return GcodeDialect::Grbl;
  if (name == "linuxcnc") return GcodeDialect::LinuxCnc;
  throw InvalidArgumentError("--dialect '" + name + "': expected grbl or linuxcnc");
}

std::string dialect_name(GcodeDialect dialect) { return dialect == GcodeDialect::Grbl ? "grbl" : "linuxcnc"; }

std::string write_gcode(const std::vector<Toolpath>& paths, const Stock& stock, const GcodeOptions& o) {
  const bool cnc = o.dialect == GcodeDialect::LinuxCnc;
  Writer w(o);
  if (cnc) w.line("%");
  for (const std::string& h : o.header) w.text_ += comment(h);
  w.text_ += comment("stock " + num(stock.x) + " x " + num(stock.y) + " x " + num(stock.z) + " mm, units mm");
  w.text_ += comment("origin: X0 Y0 at the stock corner of least x and y,");
  w.text_ += comment("Z0 at the stock bottom = the block's base on the table");
  for (std::size_t t = 0; t < paths.size(); ++t)
    w.text_ += comment("tool " + std::to_string(t + 1) + ": " + tool_description(paths[t].tool) + ", " + paths[t].role +
                       ", safe Z" + num(paths[t].safe_z));
  w.text_ += comment("dialect " + dialect_name(o.dialect) + "; feed " + num(o.feeds.feed) + ", plunge " +
                     num(o.feeds.plunge) + " mm/min; spindle " + num(o.rpm) + " rpm");
  w.line("G17 G21 G90 G94");
  for (std::size_t t = 0; t < paths.size(); ++t) {
    const Toolpath& p = paths[t];
    const std::string what = "tool " + std::to_string(t + 1) + ": " + tool_description(p.tool) + ", " + p.role;
    if (t > 0) {
      w.text_ += comment("change to " + what + "; set Z0 on the stock bottom, then resume", cnc);
      w.line("M0");
    } else {
      w.text_ += comment(what);
    }
    w.rapid_up(p.safe_z);
    if (!p.moves.empty())  // across at the safe height first: the start is unknown
      w.move({MoveKind::Rapid, Vec3(p.moves.front().to.x(), p.moves.front().to.y(), p.safe_z)});
    char spindle[64];
    std::snprintf(spindle, sizeof spindle, "S%.3f M3", o.rpm);
    w.line(spindle);
    if (o.coolant) w.line("M8");
    for (const Move& m : p.moves) w.move(m);
    if (o.coolant) w.line("M9");
    w.line("M5");
  }
  w.text_ += comment("end of program");
  w.line(cnc ? "M2" : "M30");
  if (cnc) w.line("%");
  return w.text_;
}

}  // namespace subfab
