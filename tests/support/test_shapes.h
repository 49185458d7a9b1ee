// SPDX-License-Identifier: GPL-3.0-or-later
//! Tiny meshes with known answers for the check tests.
#pragma once

#include <cmath>
#include <numbers>
#include <utility>

#include "subfab/mesh/mesh.h"

namespace subfab::test {

//! Unit right tetrahedron, outward: volume 1/6.
inline Mesh tetrahedron(const Vec3& origin = Vec3::Zero(), double size = 1.0) {
  Mesh m;
  m.vertices = {origin, origin + Vec3(size, 0, 0), origin + Vec3(0, size, 0),
                origin + Vec3(0, 0, size)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

//! Axis-aligned cube [origin, origin + size]^3, 12 outward triangles;
//! vertex x + 2y + 4z sits at corner (x, y, z). Faces 2k, 2k+1 form one side
//! (0-1: z = 0, 2-3: z = 1, 4-5: y = 0, 6-7: y = 1, 8-9: x = 0, 10-11: x = 1).
inline Mesh cube(const Vec3& origin = Vec3::Zero(), double size = 1.0) {
  Mesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back(origin + size * Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  m.faces = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
             {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

//! Appends `b` to `a` (vertices of b renumbered after a's).
inline Mesh append(Mesh a, const Mesh& b) {
  const int offset = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto t : b.faces) a.faces.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  return a;
}

//! Reverses every face.
inline Mesh flipped(Mesh m) {
  for (auto& t : m.faces) std::swap(t[1], t[2]);
  return m;
}

//! Torus of revolution (genus 1), n x m quads split in two, outward.
inline Mesh torus(int n = 12, int m = 8, double big = 2.0, double small = 0.5,
                  const Vec3& centre = Vec3::Zero()) {
  Mesh mesh;
  const double pi = std::numbers::pi;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * pi * i / n, v = 2 * pi * j / m;
      mesh.vertices.push_back(centre + Vec3((big + small * std::cos(v)) * std::cos(u),
                                            (big + small * std::cos(v)) * std::sin(u),
                                            small * std::sin(v)));
    }
  const auto id = [&](int i, int j) { return ((i + n) % n) * m + (j + m) % m; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      mesh.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return mesh;
}

}  // namespace subfab::test
