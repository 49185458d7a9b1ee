// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/read_skeleton.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "subfab/core/error.h"

namespace subfab {
namespace {

//! Next line that is neither blank nor a comment; false at the end.
bool next_line(std::istream& in, std::string& line, int& line_number) {
  while (std::getline(in, line)) {
    ++line_number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    return true;
  }
  return false;
}

}  // namespace

Skeleton read_skeleton(std::istream& in, const std::string& name) {
  int line_number = 0;
  std::string line;
  auto fail = [&](const std::string& what) -> IoError {
    return IoError(name + ":" + std::to_string(line_number) + ": " + what +
                   " (expected the .skel format: a header line, the node count, then one line per node "
                   "'id x y z radius n neighbour_1 ... neighbour_n')");
  };
  if (!next_line(in, line, line_number)) throw IoError(name + ": empty file, not a .skel skeleton");
  // optional header line: starts with a letter ("ID Cx Cy Cz RADIUS ...")
  if (std::isalpha(static_cast<unsigned char>(line[line.find_first_not_of(" \t\r")]))) {
    if (!next_line(in, line, line_number)) throw fail("missing node count");
  }
  long long count = -1;
  {
    std::istringstream s(line);
    std::string rest;
    if (!(s >> count) || (s >> rest) || count < 0) throw fail("missing node count (a single non-negative integer)");
  }
  Skeleton skeleton;
  std::vector<int> lines(static_cast<std::size_t>(count));
  for (long long v = 0; v < count; ++v) {
    if (!next_line(in, line, line_number))
      throw fail("file ends after " + std::to_string(v) + " of " + std::to_string(count) + " nodes");
    std::istringstream s(line);
    long long id = -1, num = -1;
    double x, y, z, r;
    if (!(s >> id >> x >> y >> z >> r >> num)) throw fail("malformed node line");
    if (id != v) throw fail("node id " + std::to_string(id) + " where " + std::to_string(v) + " was expected");
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) throw fail("non-finite coordinate");
    if (!(r > 0) || !std::isfinite(r)) throw fail("radius must be positive and finite");
    if (num < 0 || num > count) throw fail("bad neighbour count " + std::to_string(num));
    skeleton.add_node(Vec3(x, y, z), r);
    lines[static_cast<std::size_t>(v)] = line_number;
    auto& nb = skeleton.neighbors.back();
    for (long long i = 0; i < num; ++i) {
      long long w;
      if (!(s >> w)) throw fail("node " + std::to_string(v) + " lists fewer neighbours than its count " + std::to_string(num));
      if (w < 0 || w >= count)
        throw fail("neighbour index " + std::to_string(w) + " out of range [0, " + std::to_string(count) + ")");
      if (w == v) throw fail("node " + std::to_string(v) + " is its own neighbour");
      if (std::find(nb.begin(), nb.end(), static_cast<int>(w)) != nb.end())
        throw fail("neighbour " + std::to_string(w) + " listed twice");
      nb.push_back(static_cast<int>(w));
    }
    std::string extra;
    if (s >> extra) throw fail("more values than the neighbour count " + std::to_string(num) + " announces");
  }
  for (std::size_t v = 0; v < skeleton.num_nodes(); ++v)
    for (int w : skeleton.neighbors[v]) {
      const auto& back = skeleton.neighbors[static_cast<std::size_t>(w)];
      if (std::find(back.begin(), back.end(), static_cast<int>(v)) == back.end()) {
        line_number = lines[v];
        throw fail("node " + std::to_string(v) + " lists " + std::to_string(w) + " as a neighbour but node " +
                   std::to_string(w) + " does not list it back");
      }
    }
  return skeleton;
}

Skeleton read_skeleton(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw IoError("cannot open skeleton file " + path.string() + ": check the path");
  return read_skeleton(in, path.string());
}

}  // namespace subfab
