// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/subdivide_hex_mesh.h"

#include <algorithm>

#include "hex/hex_splitter.h"

namespace subfab {
namespace detail {

HexSplitter::HexSplitter(const HexMesh& in, HexMesh& out) : in_(in), out_(out) { out_.vertices = in_.vertices; }

int HexSplitter::add(const Vec3& p) {
  out_.vertices.push_back(p);
  return static_cast<int>(out_.vertices.size()) - 1;
}

int HexSplitter::edge(int a, int b) {
  const auto key = std::make_pair(std::min(a, b), std::max(a, b));
  auto it = edge_mid_.find(key);
  if (it != edge_mid_.end()) return it->second;
  const auto& p = in_.vertices;
  const int v = add(0.5 * (p[static_cast<std::size_t>(a)] + p[static_cast<std::size_t>(b)]));
  edge_mid_.emplace(key, v);
  return v;
}

int HexSplitter::face(int a, int b, int c, int d) {
  std::array<int, 4> key{a, b, c, d};
  std::sort(key.begin(), key.end());
  auto it = face_mid_.find(key);
  if (it != face_mid_.end()) return it->second;
  const auto& p = in_.vertices;
  auto P = [&](int v) -> const Vec3& { return p[static_cast<std::size_t>(v)]; };
  const int v = add(0.25 * (P(a) + P(b) + P(c) + P(d)));
  face_mid_.emplace(key, v);
  return v;
}

void HexSplitter::split(const Hex& h) { split(h, {true, true, true}); }

void HexSplitter::split(const Hex& h, const std::array<bool, 3>& axes) {
  // a 3 x 3 x 3 lattice g[i][j][k] of the hex's local coordinates; along an
  // axis that is not split only 0 and 2 are used
  int g[3][3][3];
  auto corner = [&](int i, int j, int k) {  // i, j, k in {0, 1}
    static constexpr int map[2][2] = {{0, 3}, {1, 2}};  // (i, j) -> VTK corner of the bottom quad
    return h[static_cast<std::size_t>(map[i][j] + 4 * k)];
  };
  const bool si = axes[0], sj = axes[1], sk = axes[2];
  for (int i = 0; i < 3; i += 2)
    for (int j = 0; j < 3; j += 2)
      for (int k = 0; k < 3; k += 2) g[i][j][k] = corner(i / 2, j / 2, k / 2);
  // edges
  if (si)
    for (int j = 0; j < 3; j += 2)
      for (int k = 0; k < 3; k += 2) g[1][j][k] = edge(g[0][j][k], g[2][j][k]);
  if (sj)
    for (int i = 0; i < 3; i += 2)
      for (int k = 0; k < 3; k += 2) g[i][1][k] = edge(g[i][0][k], g[i][2][k]);
  if (sk)
    for (int i = 0; i < 3; i += 2)
      for (int j = 0; j < 3; j += 2) g[i][j][1] = edge(g[i][j][0], g[i][j][2]);
  // faces
  if (sj && sk)
    for (int i = 0; i < 3; i += 2) g[i][1][1] = face(g[i][0][0], g[i][2][0], g[i][2][2], g[i][0][2]);
  if (si && sk)
    for (int j = 0; j < 3; j += 2) g[1][j][1] = face(g[0][j][0], g[2][j][0], g[2][j][2], g[0][j][2]);
  if (si && sj)
    for (int k = 0; k < 3; k += 2) g[1][1][k] = face(g[0][0][k], g[2][0][k], g[2][2][k], g[0][2][k]);
  // centre
  if (si && sj && sk) {
    Vec3 c = Vec3::Zero();
    for (int v : h) c += in_.vertices[static_cast<std::size_t>(v)] / 8.0;
    g[1][1][1] = add(c);
  }
  const int di = si ? 1 : 2, dj = sj ? 1 : 2, dk = sk ? 1 : 2;
  for (int k = 0; k < 2; k += dk)
    for (int j = 0; j < 2; j += dj)
      for (int i = 0; i < 2; i += di)
        out_.hexes.push_back({g[i][j][k], g[i + di][j][k], g[i + di][j + dj][k], g[i][j + dj][k], g[i][j][k + dk],
                              g[i + di][j][k + dk], g[i + di][j + dj][k + dk], g[i][j + dj][k + dk]});
}

}  // namespace detail

HexMesh subdivide_hex_mesh(const HexMesh& mesh) {
  HexMesh out;
  detail::HexSplitter splitter(mesh, out);
  for (const Hex& h : mesh.hexes) splitter.split(h);
  return out;
}

}  // namespace subfab
