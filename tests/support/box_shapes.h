// SPDX-License-Identifier: GPL-3.0-or-later
//! Small closed solids with known decompositions, shared by the tests of
//! solid_index, grow_boxes and refine_mesh: an axis-aligned box and prisms
//! (extruded polygons: L and T shapes).
#pragma once

#include <utility>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab::test {

//! Closed, outward-oriented mesh of the box [lo, hi] (12 triangles).
inline Mesh make_box_mesh(const Vec3& lo, const Vec3& hi) {
  Mesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.emplace_back((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.faces.push_back({q[0], q[1], q[2]});
    m.faces.push_back({q[0], q[2], q[3]});
  }
  return m;
}

//! Closed mesh of the prism polygon x [z0, z1]. `polygon` is a simple
//! counter-clockwise polygon (xy) that is star-shaped from `centre`; caps are
//! fans from `centre`, walls two triangles per edge.
inline Mesh make_prism(const std::vector<std::pair<double, double>>& polygon, std::pair<double, double> centre,
                       double z0, double z1) {
  Mesh m;
  const int n = static_cast<int>(polygon.size());
  for (const auto& [x, y] : polygon) m.vertices.emplace_back(x, y, z0);
  for (const auto& [x, y] : polygon) m.vertices.emplace_back(x, y, z1);
  const int c0 = 2 * n, c1 = 2 * n + 1;
  m.vertices.emplace_back(centre.first, centre.second, z0);
  m.vertices.emplace_back(centre.first, centre.second, z1);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.faces.push_back({c0, j, i});          // bottom (facing -z)
    m.faces.push_back({c1, n + i, n + j});  // top (facing +z)
    m.faces.push_back({i, j, n + j});       // wall
    m.faces.push_back({i, n + j, n + i});
  }
  return m;
}

//! L shape: [0,2]x[0,1] union [0,1]x[0,2], extruded over z in [0, 1].
inline Mesh make_l_shape() {
  return make_prism({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, {0.5, 0.5}, 0, 1);
}

//! T shape: stem [1,2]x[0,2] under the bar [0,3]x[2,3], extruded over z in [0, 1].
inline Mesh make_t_shape() {
  return make_prism({{1, 0}, {2, 0}, {2, 2}, {3, 2}, {3, 3}, {0, 3}, {0, 2}, {1, 2}}, {1.5, 2.5}, 0, 1);
}

//! The cube [0, 10]^3 with a notch cut from its top: x, y in [3, 7], z in
//! [6, 10] (walls facing into the notch, floor facing +z; 28 triangles).
inline Mesh make_notched_cube() {
  Mesh m;
  m.vertices = {{0, 0, 0},  {10, 0, 0},  {10, 10, 0},  {0, 10, 0},  {0, 0, 10}, {10, 0, 10},
                {10, 10, 10}, {0, 10, 10}, {3, 3, 10}, {7, 3, 10}, {7, 7, 10}, {3, 7, 10},
                {3, 3, 6},  {7, 3, 6},   {7, 7, 6},    {3, 7, 6}};
  m.faces = {{0, 2, 1},   {0, 3, 2},   {0, 1, 5},   {0, 5, 4},   {1, 2, 6},   {1, 6, 5},
             {2, 3, 7},   {2, 7, 6},   {3, 0, 4},   {3, 4, 7},   {4, 5, 9},   {4, 9, 8},
             {5, 6, 10},  {5, 10, 9},  {6, 7, 11},  {6, 11, 10}, {7, 4, 8},   {7, 8, 11},
             {8, 9, 13},  {8, 13, 12}, {9, 10, 14}, {9, 14, 13}, {10, 11, 15}, {10, 15, 14},
             {11, 8, 12}, {11, 12, 15}, {12, 13, 14}, {12, 14, 15}};
  return m;
}

}  // namespace subfab::test
