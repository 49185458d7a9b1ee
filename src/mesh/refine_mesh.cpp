// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mesh/refine_mesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>

#include "subfab/core/error.h"

namespace subfab {
namespace {

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

}  // namespace

RefineResult refine_mesh(const Mesh& mesh, const std::vector<int>& faces) {
  const int nf = static_cast<int>(mesh.faces.size());
  std::vector<char> red(static_cast<std::size_t>(nf), 0);
  for (int f : faces) {
    if (f < 0 || f >= nf)
      throw InvalidArgumentError("refine_mesh: face id " + std::to_string(f) + " out of range (mesh has " +
                                 std::to_string(nf) + " faces)");
    red[static_cast<std::size_t>(f)] = 1;
  }
  // Split edges (value: midpoint vertex id, assigned later in a deterministic order).
  std::unordered_map<std::uint64_t, int> split;
  std::unordered_map<std::uint64_t, std::vector<int>> edge_faces;
  for (int f = 0; f < nf; ++f) {
    const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
    for (int e = 0; e < 3; ++e) edge_faces[edge_key(t[e], t[(e + 1) % 3])].push_back(f);
  }
  std::vector<int> queue;
  for (int f = 0; f < nf; ++f)
    if (red[static_cast<std::size_t>(f)]) queue.push_back(f);
  auto num_split_edges = [&](int f) {
    const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
    int n = 0;
    for (int e = 0; e < 3; ++e) n += split.count(edge_key(t[e], t[(e + 1) % 3])) ? 1 : 0;
    return n;
  };
  // Red closure: mark the edges of red faces; neighbours with >= 2 split
  // edges become red.
  while (!queue.empty()) {
    const int f = queue.back();
    queue.pop_back();
    const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
    for (int e = 0; e < 3; ++e) {
      const std::uint64_t key = edge_key(t[e], t[(e + 1) % 3]);
      if (split.count(key)) continue;
      split.emplace(key, -1);
      for (int g : edge_faces[key]) {
        if (red[static_cast<std::size_t>(g)]) continue;
        if (num_split_edges(g) >= 2) {
          red[static_cast<std::size_t>(g)] = 1;
          queue.push_back(g);
        }
      }
    }
  }
  RefineResult result;
  result.mesh.vertices = mesh.vertices;
  // Midpoints in face order, edge order: deterministic ids.
  for (int f = 0; f < nf; ++f) {
    const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
    for (int e = 0; e < 3; ++e) {
      auto it = split.find(edge_key(t[e], t[(e + 1) % 3]));
      if (it == split.end() || it->second >= 0) continue;
      it->second = static_cast<int>(result.mesh.vertices.size());
      const Vec3& p = mesh.vertices[static_cast<std::size_t>(t[e])];
      const Vec3& q = mesh.vertices[static_cast<std::size_t>(t[(e + 1) % 3])];
      result.mesh.vertices.push_back(0.5 * (p + q));
    }
  }
  result.mesh.faces = mesh.faces;
  result.parent.resize(static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) result.parent[static_cast<std::size_t>(f)] = f;
  auto add = [&](int f, const Triangle& child, bool first) {
    if (first) {
      result.mesh.faces[static_cast<std::size_t>(f)] = child;
    } else {
      result.mesh.faces.push_back(child);
      result.parent.push_back(f);
    }
  };
  for (int f = 0; f < nf; ++f) {
    const Triangle t = mesh.faces[static_cast<std::size_t>(f)];
    std::array<int, 3> mid{};  // midpoint of edge (t[e], t[e+1]), -1 if not split
    int count = 0;
    for (int e = 0; e < 3; ++e) {
      auto it = split.find(edge_key(t[e], t[(e + 1) % 3]));
      mid[static_cast<std::size_t>(e)] = it == split.end() ? -1 : it->second;
      count += it == split.end() ? 0 : 1;
    }
    if (count == 3) {
      const int a = t[0], b = t[1], c = t[2];
      const int ab = mid[0], bc = mid[1], ca = mid[2];
      add(f, {a, ab, ca}, true);
      add(f, {ab, b, bc}, false);
      add(f, {ca, bc, c}, false);
      add(f, {ab, bc, ca}, false);
      ++result.num_split_1to4;
    } else if (count == 1) {
      int e = 0;
      while (mid[static_cast<std::size_t>(e)] < 0) ++e;
      const int p = t[e], q = t[(e + 1) % 3], r = t[(e + 2) % 3], m = mid[static_cast<std::size_t>(e)];
      add(f, {p, m, r}, true);
      add(f, {m, q, r}, false);
      ++result.num_split_1to2;
    }
    // count == 2 cannot happen after the red closure.
  }
  return result;
}

}  // namespace subfab
