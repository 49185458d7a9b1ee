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

void HexSplitter::split(const Hex& h) {
  // a 3 x 3 x 3 lattice g[i][j][k] of the hex's local coordinates
  int g[3][3][3];
  auto corner = [&](int i, int j, int k) {  // i, j, k in {0, 1}
    static constexpr int map[2][2] = {{0, 3}, {1, 2}};  // (i, j) -> VTK corner of the bottom quad
    return h[static_cast<std::size_t>(map[i][j] + 4 * k)];
  };
  for (int i = 0; i < 3; i += 2)
    for (int j = 0; j < 3; j += 2)
      for (int k = 0; k < 3; k += 2) g[i][j][k] = corner(i / 2, j / 2, k / 2);
  // edges
  for (int j = 0; j < 3; j += 2)
    for (int k = 0; k < 3; k += 2) g[1][j][k] = edge(g[0][j][k], g[2][j][k]);
  for (int i = 0; i < 3; i += 2)
    for (int k = 0; k < 3; k += 2) g[i][1][k] = edge(g[i][0][k], g[i][2][k]);
  for (int i = 0; i < 3; i += 2)
    for (int j = 0; j < 3; j += 2) g[i][j][1] = edge(g[i][j][0], g[i][j][2]);
  // faces
  for (int i = 0; i < 3; i += 2) g[i][1][1] = face(g[i][0][0], g[i][2][0], g[i][2][2], g[i][0][2]);
  for (int j = 0; j < 3; j += 2) g[1][j][1] = face(g[0][j][0], g[2][j][0], g[2][j][2], g[0][j][2]);
  for (int k = 0; k < 3; k += 2) g[1][1][k] = face(g[0][0][k], g[2][0][k], g[2][2][k], g[0][2][k]);
  // centre
  Vec3 c = Vec3::Zero();
  for (int v : h) c += in_.vertices[static_cast<std::size_t>(v)] / 8.0;
  g[1][1][1] = add(c);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        out_.hexes.push_back({g[i][j][k], g[i + 1][j][k], g[i + 1][j + 1][k], g[i][j + 1][k], g[i][j][k + 1],
                              g[i + 1][j][k + 1], g[i + 1][j + 1][k + 1], g[i][j + 1][k + 1]});
}

}  // namespace detail

HexMesh subdivide_hex_mesh(const HexMesh& mesh) {
  HexMesh out;
  detail::HexSplitter splitter(mesh, out);
  for (const Hex& h : mesh.hexes) splitter.split(h);
  return out;
}

}  // namespace subfab
