// SPDX-License-Identifier: GPL-3.0-or-later
//! Small tubular shapes and skeletons with known answers for the hex tests.
#pragma once

#include <cmath>
#include <numbers>

#include <algorithm>

#include "subfab/hex/hex_mesh.h"
#include "subfab/hex/scaled_jacobian.h"
#include "subfab/hex/skeleton.h"
#include "subfab/mesh/mesh.h"
#include "support/test_shapes.h"

namespace subfab::test {

//! Capsule along x: a cylinder of radius r from x = -h to x = h closed by two
//! hemispheres; `around` segments around, `rings` rings per hemisphere,
//! `along` segments along the cylinder. Outward oriented, closed.
inline Mesh capsule(double r = 1.0, double h = 3.0, int around = 24, int rings = 8, int along = 12) {
  Mesh mesh;
  const double pi = std::numbers::pi;
  // ring list: (x, radius) from the left pole to the right pole, poles excluded
  std::vector<std::pair<double, double>> profile;
  for (int i = 1; i <= rings; ++i) {
    const double a = pi / 2 * (1.0 - static_cast<double>(i) / rings);  // from pi/2 down to 0
    profile.push_back({-h - r * std::sin(a), r * std::cos(a)});
  }
  for (int i = 1; i < along; ++i) profile.push_back({-h + 2 * h * i / along, r});
  for (int i = 0; i < rings; ++i) {
    const double a = pi / 2 * static_cast<double>(i) / rings;
    profile.push_back({h + r * std::sin(a), r * std::cos(a)});
  }
  mesh.vertices.push_back(Vec3(-h - r, 0, 0));
  for (const auto& [x, rad] : profile)
    for (int j = 0; j < around; ++j) {
      const double t = 2 * pi * j / around;
      mesh.vertices.push_back(Vec3(x, rad * std::cos(t), rad * std::sin(t)));
    }
  mesh.vertices.push_back(Vec3(h + r, 0, 0));
  const int nr = static_cast<int>(profile.size());
  const int last = static_cast<int>(mesh.vertices.size()) - 1;
  auto id = [&](int ring, int j) { return 1 + ring * around + (j + around) % around; };
  for (int j = 0; j < around; ++j) mesh.faces.push_back({0, id(0, j + 1), id(0, j)});
  for (int i = 0; i + 1 < nr; ++i)
    for (int j = 0; j < around; ++j) {
      mesh.faces.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
      mesh.faces.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
    }
  for (int j = 0; j < around; ++j) mesh.faces.push_back({last, id(nr - 1, j), id(nr - 1, j + 1)});
  return mesh;
}

//! A straight chain of `n` nodes from (-h,0,0) to (h,0,0), radius r.
inline Skeleton line_skeleton(int n = 7, double h = 3.0, double r = 1.0) {
  Skeleton s;
  for (int i = 0; i < n; ++i) s.add_node(Vec3(-h + 2 * h * i / (n - 1), 0, 0), r);
  for (int i = 0; i + 1 < n; ++i) s.add_edge(i, i + 1);
  return s;
}

//! A Y: centre node 0 at the origin and three straight branches of `n`
//! further nodes each, in the xy plane at 90, 210 and 330 degrees, length L.
inline Skeleton y_skeleton(int n = 6, double length = 4.0, double r = 0.5) {
  Skeleton s;
  s.add_node(Vec3::Zero(), r);
  const double pi = std::numbers::pi;
  for (int b = 0; b < 3; ++b) {
    const double a = pi / 2 + 2 * pi * b / 3;
    int prev = 0;
    for (int i = 1; i <= n; ++i) {
      const int v = s.add_node(length * i / n * Vec3(std::cos(a), std::sin(a), 0), r);
      s.add_edge(prev, v);
      prev = v;
    }
  }
  return s;
}

//! A ring of `n` nodes on the circle of radius `big` in the xy plane, radius r.
inline Skeleton ring_skeleton(int n = 16, double big = 2.0, double r = 0.5) {
  Skeleton s;
  const double pi = std::numbers::pi;
  for (int i = 0; i < n; ++i) s.add_node(big * Vec3(std::cos(2 * pi * i / n), std::sin(2 * pi * i / n), 0), r);
  for (int i = 0; i < n; ++i) s.add_edge(i, (i + 1) % n);
  return s;
}

//! A grid of nx x ny x nz unit hexahedra filling [0,nx] x [0,ny] x [0,nz]
//! (VTK order); vertex (i,j,k) has index i + (nx+1) (j + (ny+1) k).
inline HexMesh hex_grid(int nx, int ny, int nz) {
  HexMesh m;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.vertices.push_back(Vec3(i, j, k));
  auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.hexes.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                           id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)});
  return m;
}

//! The unit cube [0,1]^3 as one hexahedron (VTK order).
inline HexMesh unit_hex_cube() {
  HexMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
  m.hexes = {{0, 1, 2, 3, 4, 5, 6, 7}};
  return m;
}

//! Worst scaled Jacobian of a mesh.
inline double min_sj(const HexMesh& m) {
  const auto sj = scaled_jacobians(m);
  return *std::min_element(sj.begin(), sj.end());
}

//! n x n x n unit hexahedra filling the cube [0,n]^3, its surface the cube;
//! vertex (i,j,k).
struct GridInCube {
  explicit GridInCube(int n) : n(n), mesh(hex_grid(n, n, n)), surface(cube(Vec3::Zero(), n)) {}
  std::size_t id(int i, int j, int k) const { return static_cast<std::size_t>(i + (n + 1) * (j + (n + 1) * k)); }
  int n;
  HexMesh mesh;
  Mesh surface;
};

}  // namespace subfab::test
