// SPDX-License-Identifier: GPL-3.0-or-later
#include "decompose/single_precision_cleanup.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "subfab/checks/check_self_intersections.h"
#include "subfab/validate/check_single_precision.h"

namespace subfab::detail {
namespace {

double to_float(double x) { return static_cast<double>(static_cast<float>(x)); }

//! The float on the other side of x from its rounding (x between them).
double other_float(double x) {
  const float f = static_cast<float>(x);
  if (static_cast<double>(f) == x) return x;
  return static_cast<double>(std::nextafter(f, static_cast<double>(f) < x ? std::numeric_limits<float>::infinity()
                                                                         : -std::numeric_limits<float>::infinity()));
}

//! Merges vertices of `machine` that are equal (already floats), applies the
//! same merge to `block`, and removes the faces that lost their area (a
//! repeated vertex) and coincident pairs of opposite faces.
void collapse(Mesh& machine, Mesh& block, SinglePrecisionCleanup& r) {
  std::map<std::array<double, 3>, int> first;
  std::vector<int> to(machine.num_vertices());
  for (std::size_t v = 0; v < machine.num_vertices(); ++v) {
    const Vec3& p = machine.vertices[v];
    const auto [it, added] = first.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, static_cast<int>(v));
    to[v] = it->second;
    if (!added) {
      ++r.num_collapsed;
      block.vertices[v] = block.vertices[static_cast<std::size_t>(it->second)];
    }
  }
  if (r.num_collapsed == 0) return;
  std::vector<Triangle> faces;
  std::map<std::array<int, 3>, std::size_t> seen;  // sorted corners -> index in faces
  std::vector<char> removed;
  for (Triangle f : machine.faces) {
    for (int& v : f) v = to[static_cast<std::size_t>(v)];
    if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) {
      ++r.num_faces_removed;
      continue;
    }
    std::array<int, 3> key{f[0], f[1], f[2]};
    std::sort(key.begin(), key.end());
    if (const auto it = seen.find(key); it != seen.end() && !removed[it->second]) {
      removed[it->second] = 1;  // the same triangle twice (a collapsed sheet's two sides): both go
      r.num_faces_removed += 2;
      continue;
    }
    seen[key] = faces.size();
    faces.push_back(f);
    removed.push_back(0);
  }
  machine.faces.clear();
  for (std::size_t k = 0; k < faces.size(); ++k)
    if (!removed[k]) machine.faces.push_back(faces[k]);
  block.faces = machine.faces;
  remove_unreferenced_vertices(block);  // same order as in machine: unreferenced ids are the same
  remove_unreferenced_vertices(machine);
}

std::size_t num_crossing(const Mesh& m) { return check_self_intersections(m, {.max_examples = 64}).num_offending; }

}  // namespace

SinglePrecisionCleanup clean_single_precision(Mesh& machine, Mesh& block) {
  SinglePrecisionCleanup r;
  if (check_single_precision(machine).ok()) return r;
  std::vector<Vec3> exact = machine.vertices;  // before rounding, for the other rounding
  for (Vec3& v : machine.vertices) v = Vec3(to_float(v.x()), to_float(v.y()), to_float(v.z()));
  collapse(machine, block, r);
  if (r.num_collapsed > 0) exact = machine.vertices;  // ids changed: nudge from the floats
  // Nudge the vertices of crossing faces, at most 3 passes.
  for (int pass = 0; pass < 3; ++pass) {
    const CheckResult crossing = check_self_intersections(machine, {.max_examples = 64});
    if (crossing.num_offending == 0) break;
    std::set<int> vertices;
    for (int f : crossing.examples)
      for (int v : machine.faces[static_cast<std::size_t>(f)]) vertices.insert(v);
    std::size_t best = crossing.num_offending;
    for (int v : vertices) {
      const std::size_t vs = static_cast<std::size_t>(v);
      const Vec3 rounded = machine.vertices[vs], other(other_float(exact[vs].x()), other_float(exact[vs].y()),
                                                       other_float(exact[vs].z()));
      Vec3 keep = rounded;
      for (int mask = 1; mask < 8; ++mask) {
        Vec3 candidate = rounded;
        for (int k = 0; k < 3; ++k)
          if (mask & (1 << k)) candidate[k] = other[k];
        if (candidate == rounded) continue;
        machine.vertices[vs] = candidate;
        const std::size_t count = num_crossing(machine);
        if (count < best) {
          best = count;
          keep = candidate;
        }
      }
      machine.vertices[vs] = keep;
      if (keep != rounded) ++r.num_nudged;
      if (best == 0) break;
    }
  }
  r.ok = check_single_precision(machine).ok();
  return r;
}

}  // namespace subfab::detail
