// SPDX-License-Identifier: GPL-3.0-or-later
//! Small shapes with known answers for the smoothing tests (taubin_smooth,
//! smooth_for_decomposition, restore_details, decompose_smoothed): a finely
//! gridded cube (with a bump), an icosphere, radial noise, an inverted copy
//! (a cavity).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

#include "subfab/mesh/mesh.h"

namespace subfab::test {

//! The cube [lo, lo + size]^3, each face an n x n grid of squares split in
//! two triangles, outward oriented, vertices shared (welded).
inline Mesh grid_cube(int n, double size = 1.0, const Vec3& lo = Vec3::Zero()) {
  Mesh mesh;
  // Face k: normal along axis k, side s (0 = low, 1 = high).
  for (int k = 0; k < 3; ++k)
    for (int s = 0; s < 2; ++s) {
      const int u = (k + 1) % 3, v = (k + 2) % 3;
      const int base = static_cast<int>(mesh.vertices.size());
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          Vec3 p;
          p[k] = s * size;
          p[u] = size * i / n;
          p[v] = size * j / n;
          mesh.vertices.push_back(lo + p);
        }
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const int a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
          // (u, v, k) is right-handed: counter-clockwise in (u, v) faces +k.
          if (s == 1) {
            mesh.faces.push_back({a, b, d});
            mesh.faces.push_back({a, d, c});
          } else {
            mesh.faces.push_back({a, d, b});
            mesh.faces.push_back({a, c, d});
          }
        }
    }
  weld_identical_vertices(mesh);
  return mesh;
}

//! grid_cube(n) with a Gaussian bump of height `height` on its top face
//! around (0.5, 0.5); with `lean` > 0 the bump's top is also pushed along +x
//! by lean x (its profile)^2, which folds it over: faces on its +x side face
//! down (an undercut along +z).
inline Mesh bumped_cube(int n, double height, double lean = 0.0) {
  Mesh m = grid_cube(n);
  for (Vec3& p : m.vertices) {
    if (p.z() != 1.0 || p.x() <= 0 || p.x() >= 1 || p.y() <= 0 || p.y() >= 1) continue;
    const double r2 = (p.x() - 0.5) * (p.x() - 0.5) + (p.y() - 0.5) * (p.y() - 0.5);
    const double g = std::exp(-r2 / 0.02);
    p.z() += height * g;
    p.x() += lean * g * g;
  }
  return m;
}

//! Unit icosphere around `centre` (radius `radius`): an icosahedron split
//! 1-to-4 `level` times, vertices on the sphere, outward oriented.
inline Mesh icosphere(int level, double radius = 1.0, const Vec3& centre = Vec3::Zero()) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  Mesh m;
  m.vertices = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (Vec3& p : m.vertices) p.normalize();
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> midpoint;
    const auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      m.vertices.push_back((m.vertices[static_cast<std::size_t>(a)] + m.vertices[static_cast<std::size_t>(b)]).normalized());
      const int id = static_cast<int>(m.vertices.size()) - 1;
      midpoint.emplace(key, id);
      return id;
    };
    std::vector<Triangle> faces;
    for (const Triangle& f : m.faces) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      faces.push_back({f[0], ab, ca});
      faces.push_back({f[1], bc, ab});
      faces.push_back({f[2], ca, bc});
      faces.push_back({ab, bc, ca});
    }
    m.faces = std::move(faces);
  }
  for (Vec3& p : m.vertices) p = centre + radius * p;
  return m;
}

//! Deterministic pseudo-random number in [-1, 1] for index i.
inline double hash_noise(std::size_t i) {
  std::uint64_t x = i * 0x9E3779B97F4A7C15ULL + 0x632BE59BD9B4E019ULL;
  x ^= x >> 31;
  x *= 0xBF58476D1CE4E5B9ULL;
  x ^= x >> 29;
  return static_cast<double>(x % 2000001) / 1000000.0 - 1.0;
}

//! Moves every vertex radially (from `centre`) by amplitude x hash_noise(v).
inline Mesh radial_noise(Mesh m, double amplitude, const Vec3& centre = Vec3::Zero()) {
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    const Vec3 d = (m.vertices[v] - centre).normalized();
    m.vertices[v] += amplitude * hash_noise(v) * d;
  }
  return m;
}

//! The same surface with the opposite orientation (the boundary of a cavity).
inline Mesh inverted(Mesh m) {
  for (Triangle& f : m.faces) std::swap(f[1], f[2]);
  return m;
}

//! a and b as one mesh (b's vertices appended).
inline Mesh combined(Mesh a, const Mesh& b) {
  const int offset = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (Triangle f : b.faces) {
    for (int& v : f) v += offset;
    a.faces.push_back(f);
  }
  return a;
}

//! Root mean square of |p - centre| - r over the vertices, r = their mean
//! distance to `centre` (the noise around the best sphere with that centre).
inline double radial_rms(const Mesh& m, const Vec3& centre = Vec3::Zero()) {
  double radius = 0;
  for (const Vec3& p : m.vertices) radius += (p - centre).norm();
  radius /= static_cast<double>(m.vertices.size());
  double sum = 0;
  for (const Vec3& p : m.vertices) sum += std::pow((p - centre).norm() - radius, 2);
  return std::sqrt(sum / static_cast<double>(m.vertices.size()));
}

}  // namespace subfab::test
