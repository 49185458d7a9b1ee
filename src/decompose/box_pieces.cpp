// SPDX-License-Identifier: GPL-3.0-or-later
// Connected pieces of the surface inside a height box (cost predictor of the
// minimal cover, thesis 4.3.2).
#include "decompose/box_pieces.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <utility>

namespace subfab::detail {
namespace {

//! Does the segment a-b meet the closed box? (Slab clipping in doubles:
//! a predictor only, see box_pieces.h.)
bool segment_meets_closed_box(const Vec3& a, const Vec3& b, const Box3& box) {
  double lo = 0, hi = 1;
  for (int d = 0; d < 3; ++d) {
    const double delta = b[d] - a[d];
    if (delta == 0) {
      if (a[d] < box.min[d] || a[d] > box.max[d]) return false;
      continue;
    }
    double t0 = (box.min[d] - a[d]) / delta, t1 = (box.max[d] - a[d]) / delta;
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
    if (lo > hi) return false;
  }
  return true;
}

}  // namespace

std::vector<int> face_neighbours(const Mesh& mesh) {
  const std::size_t nf = mesh.faces.size();
  std::vector<int> neighbour(3 * nf, -1);
  // Directed edge (u, v) of face f at slot k; its twin is (v, u).
  std::vector<std::pair<std::pair<int, int>, int>> edges;
  edges.reserve(3 * nf);
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      edges.push_back({{mesh.faces[f][static_cast<std::size_t>(k)], mesh.faces[f][static_cast<std::size_t>((k + 1) % 3)]},
                       static_cast<int>(3 * f) + k});
  std::sort(edges.begin(), edges.end());
  for (const auto& [uv, slot] : edges) {
    const std::pair<int, int> twin{uv.second, uv.first};
    auto it = std::lower_bound(edges.begin(), edges.end(), std::make_pair(twin, -1));
    if (it != edges.end() && it->first == twin) neighbour[static_cast<std::size_t>(slot)] = it->second / 3;
  }
  return neighbour;
}

std::vector<std::vector<int>> surface_pieces(const SolidIndex& index, const std::vector<int>& neighbours,
                                             const HeightBox& box) {
  std::vector<int> faces = index.faces_meeting_open_box(box.box);
  const std::vector<int> covered = index.faces_covered(box);
  std::vector<int> all;
  std::set_union(faces.begin(), faces.end(), covered.begin(), covered.end(), std::back_inserter(all));
  faces = std::move(all);
  const std::size_t n = faces.size();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  };
  const Mesh& mesh = index.mesh();
  // Position of each face in `faces` (-1: not inside), in a buffer per thread
  // reset after use: a lookup per edge without a search.
  thread_local std::vector<int> slot;
  if (slot.size() < mesh.faces.size()) slot.assign(mesh.faces.size(), -1);
  for (std::size_t i = 0; i < n; ++i) slot[static_cast<std::size_t>(faces[i])] = static_cast<int>(i);
  for (std::size_t i = 0; i < n; ++i) {
    const int f = faces[i];
    const auto& t = mesh.faces[static_cast<std::size_t>(f)];
    for (int k = 0; k < 3; ++k) {
      const int g = neighbours[static_cast<std::size_t>(3 * f + k)];
      if (g < f) continue;  // each edge once (and -1)
      const int j = slot[static_cast<std::size_t>(g)];
      if (j < 0) continue;
      const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
      const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>((k + 1) % 3)])];
      if (!segment_meets_closed_box(a, b, box.box)) continue;
      const int ra = find(static_cast<int>(i)), rb = find(j);
      if (ra != rb) parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
    }
  }
  for (int f : faces) slot[static_cast<std::size_t>(f)] = -1;
  // Roots are the smallest index of their set (union by min): pieces in
  // order of their smallest face id.
  std::vector<int> piece_of_root(n, -1);
  std::vector<std::vector<int>> pieces;
  for (std::size_t i = 0; i < n; ++i) {
    int& piece = piece_of_root[static_cast<std::size_t>(find(static_cast<int>(i)))];
    if (piece < 0) {
      piece = static_cast<int>(pieces.size());
      pieces.emplace_back();
    }
    pieces[static_cast<std::size_t>(piece)].push_back(faces[i]);
  }
  return pieces;
}

}  // namespace subfab::detail
