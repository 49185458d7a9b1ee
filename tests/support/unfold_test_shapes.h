// SPDX-License-Identifier: GPL-3.0-or-later
//! Small polygonal solids with known answers for the facet-deletion,
//! unfolding and export tests: all facet normals are lattice directions and
//! all vertices have integer coordinates; and the lattice of a block of
//! points for the marching-cubes, chart and mask tests.
#pragma once

#include <array>
#include <map>
#include <vector>

#include "subfab/unfold/build_lattice.h"
#include "subfab/unfold/lattice_directions.h"
#include "subfab/unfold/poly_mesh.h"

namespace subfab::test {

//! Builds a PolyMesh from vertices and facets (each facet: loops of vertex
//! ids, outer loop CCW from outside); normals are computed (Newell).
inline PolyMesh make_poly(const std::vector<Vec3>& vertices, const std::vector<std::vector<std::vector<int>>>& facets) {
  PolyMesh mesh;
  mesh.vertices = vertices;
  for (const auto& loops : facets) {
    Facet f;
    f.loops = loops;
    Vec3 n = Vec3::Zero();
    const auto& l = loops[0];
    for (std::size_t i = 0; i < l.size(); ++i) n += vertices[l[i]].cross(vertices[l[(i + 1) % l.size()]]);
    f.normal = lattice_direction_index(n, 1e-6).value_or(-1);
    mesh.facets.push_back(f);
  }
  return mesh;
}

//! Extrudes a simple polygon of the xy-plane (CCW, integer coordinates)
//! from z = 0 to z = height: bottom, top and one side facet per edge.
inline PolyMesh extrude(const std::vector<std::array<double, 2>>& polygon, double height) {
  const int n = static_cast<int>(polygon.size());
  std::vector<Vec3> v;
  for (const auto& p : polygon) v.emplace_back(p[0], p[1], 0.0);
  for (const auto& p : polygon) v.emplace_back(p[0], p[1], height);
  std::vector<std::vector<std::vector<int>>> facets;
  std::vector<int> bottom, top;
  for (int i = n - 1; i >= 0; --i) bottom.push_back(i);
  for (int i = 0; i < n; ++i) top.push_back(n + i);
  facets.push_back({bottom});
  facets.push_back({top});
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    facets.push_back({{i, j, n + j, n + i}});
  }
  return make_poly(v, facets);
}

//! Axis-aligned box [0,a] x [0,b] x [0,c].
inline PolyMesh box(double a, double b, double c) { return extrude({{0, 0}, {a, 0}, {a, b}, {0, b}}, c); }

//! [0,4]^3 with its vertical edge at x = y = 4 chamfered by the plane x + y = 7.
inline PolyMesh chamfered_cube() { return extrude({{0, 0}, {4, 0}, {4, 3}, {3, 4}, {0, 4}}, 4); }

//! [0,4]^3 with the corner (4,4,4) cut by the plane x + y + z = 11.
inline PolyMesh corner_cut_cube() {
  std::vector<Vec3> v = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {0, 0, 4}, {4, 0, 4},
                         {3, 4, 4}, {0, 4, 4}, {4, 3, 4}, {4, 4, 3}};
  //  indices: 6 = (3,4,4), 8 = (4,3,4), 9 = (4,4,3)
  return make_poly(v, {
                          {{0, 3, 2, 1}},        // z = 0
                          {{4, 5, 8, 6, 7}},     // z = 4
                          {{0, 1, 5, 4}},        // y = 0
                          {{3, 0, 4, 7}},        // x = 0
                          {{1, 2, 9, 8, 5}},     // x = 4
                          {{2, 3, 7, 6, 9}},     // y = 4
                          {{8, 9, 6}},           // x + y + z = 11
                      });
}

//! [0,4] x [0,4] x [0,4] minus the notch [3,4] x [3,4] x [0,4] (Figure 3.11:
//! the riser x = 3 alone cannot be deleted, with the tread y = 3 it can).
inline PolyMesh notched_box() { return extrude({{0, 0}, {4, 0}, {4, 3}, {3, 3}, {3, 4}, {0, 4}}, 4); }

//! L-shaped prism.
inline PolyMesh l_prism() { return extrude({{0, 0}, {6, 0}, {6, 2}, {2, 2}, {2, 6}, {0, 6}}, 2); }

//! Three-step staircase prism.
inline PolyMesh staircase() {
  return extrude({{0, 0}, {6, 0}, {6, 2}, {4, 2}, {4, 4}, {2, 4}, {2, 6}, {0, 6}}, 3);
}

//! A 2 x 1 block of unit-2 cubes with all four vertical edges bevelled at 45
//! degrees (an elongated octagonal prism).
inline PolyMesh bevelled_block() {
  return extrude({{1, 0}, {3, 0}, {4, 1}, {4, 2}, {3, 3}, {1, 3}, {0, 2}, {0, 1}}, 2);
}

//! The box [0,4]^2 x [0,2] with the box [1,3]^2 x [2,3] standing on it: the
//! big box's top facet (id 1) is a square with a square hole (two loops).
inline PolyMesh box_on_box() {
  std::vector<Vec3> v;
  for (double z : {0.0, 2.0}) v.insert(v.end(), {{0, 0, z}, {4, 0, z}, {4, 4, z}, {0, 4, z}});
  for (double z : {2.0, 3.0}) v.insert(v.end(), {{1, 1, z}, {3, 1, z}, {3, 3, z}, {1, 3, z}});
  return make_poly(v, {{{0, 3, 2, 1}},
                       {{4, 5, 6, 7}, {8, 11, 10, 9}},
                       {{0, 1, 5, 4}},
                       {{1, 2, 6, 5}},
                       {{2, 3, 7, 6}},
                       {{3, 0, 4, 7}},
                       {{8, 9, 13, 12}},
                       {{9, 10, 14, 13}},
                       {{10, 11, 15, 14}},
                       {{11, 8, 12, 15}},
                       {{12, 13, 14, 15}}});
}

//! An n x n x n lattice whose inside points are the block [lo, hi]^3 (grid
//! indices, inclusive).
inline Lattice block_lattice(int n, int lo, int hi) {
  Lattice l;
  l.grid.size = {n, n, n};
  l.inside.assign(l.grid.num_points(), 0);
  for (int k = lo; k <= hi; ++k)
    for (int j = lo; j <= hi; ++j)
      for (int i = lo; i <= hi; ++i) l.inside[l.grid.index(i, j, k)] = 1;
  return l;
}

}  // namespace subfab::test
