// SPDX-License-Identifier: GPL-3.0-or-later
//! Small solids with known answers for the carve / merge / validate /
//! export tests: boxes and extruded polygons (an L, a U), built by hand.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "subfab/decompose/export_decomposition.h"
#include "subfab/geometry/height_box.h"
#include "subfab/validate/validate_decomposition.h"
#include "subfab/mesh/mesh.h"

namespace subfab::test {

//! Prism over a counter-clockwise polygon (in xy) from z0 to z1; `fan` is a
//! triangulation of the polygon (counter-clockwise triangles of its corners).
inline Mesh extrude_polygon(const std::vector<std::array<double, 2>>& polygon,
                            const std::vector<Triangle>& fan, double z0, double z1) {
  Mesh m;
  const int n = static_cast<int>(polygon.size());
  for (double z : {z0, z1})
    for (const auto& p : polygon) m.vertices.emplace_back(p[0], p[1], z);
  for (const Triangle& t : fan) {
    m.faces.push_back({n + t[0], n + t[1], n + t[2]});  // top, seen from +z
    m.faces.push_back({t[0], t[2], t[1]});              // bottom, reversed
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.faces.push_back({i, j, n + j});
    m.faces.push_back({i, n + j, n + i});
  }
  return m;
}

//! Axis-aligned box solid [min, max].
inline Mesh box_solid(const Vec3& min, const Vec3& max) {
  Mesh m = extrude_polygon({{min.x(), min.y()}, {max.x(), min.y()}, {max.x(), max.y()}, {min.x(), max.y()}},
                           {{0, 1, 2}, {0, 2, 3}}, min.z(), max.z());
  return m;
}

//! A square "barrel": squares of half-width `a` at z = 0 and z = 2h and
//! a + h tan(`lean_deg`) at z = h, joined by planar trapezoids. The four
//! lower side faces lean `lean_deg` degrees past vertical (they face down),
//! the upper ones face up: exactly two height-field blocks (the halves, along
//! +z and -z), one when faces may lean that far.
inline Mesh barrel_solid(double a, double h, double lean_deg) {
  const double w[3] = {a, a + h * std::tan(lean_deg * 3.14159265358979323846 / 180.0), a};
  Mesh m;
  for (int r = 0; r < 3; ++r)
    for (const auto& c : std::array<std::array<double, 2>, 4>{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}})
      m.vertices.emplace_back(c[0] * w[r], c[1] * w[r], r * h);
  m.faces = {{0, 2, 1}, {0, 3, 2}, {8, 9, 10}, {8, 10, 11}};  // bottom (-z), top (+z)
  for (int r = 0; r < 2; ++r)
    for (int i = 0; i < 4; ++i) {
      const int j = (i + 1) % 4, lo = 4 * r, hi = 4 * (r + 1);
      m.faces.push_back({lo + i, lo + j, hi + j});
      m.faces.push_back({lo + i, hi + j, hi + i});
    }
  return m;
}

//! L-shaped prism: the union of [0,2]x[0,1] and [0,1]x[0,2] in xy, z in [0,1]. Volume 3.
inline Mesh l_solid() {
  return extrude_polygon({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}},
                         {{3, 4, 5}, {3, 5, 0}, {3, 0, 1}, {3, 1, 2}}, 0.0, 1.0);
}

inline Box3 make_box(const Vec3& min, const Vec3& max) {
  Box3 b;
  b.min = min;
  b.max = max;
  return b;
}

inline HeightBox make_height_box(const Vec3& min, const Vec3& max, Axis axis) {
  HeightBox h;
  h.box = make_box(min, max);
  h.axis = axis;
  return h;
}

//! `m` with a zero-area face, as rounding leaves them in blocks until the
//! export cleans them: edge k of face `face` (from its corner k to the next)
//! split at its midpoint M, the face replaced by its two halves and the
//! collinear face (M, corner k, corner k + 1) closing the mesh against the
//! neighbour across that edge. Still a closed, consistently oriented mesh.
inline Mesh with_zero_area_face(Mesh m, std::size_t face, int k) {
  const Triangle t = m.faces[face];
  const int p = t[static_cast<std::size_t>(k)], q = t[static_cast<std::size_t>((k + 1) % 3)],
            r = t[static_cast<std::size_t>((k + 2) % 3)];
  const int mid = static_cast<int>(m.vertices.size());
  m.vertices.push_back(0.5 * (m.vertices[static_cast<std::size_t>(p)] + m.vertices[static_cast<std::size_t>(q)]));
  m.faces[face] = {p, mid, r};
  m.faces.push_back({mid, q, r});
  m.faces.push_back({mid, p, q});  // zero area
  return m;
}

//! Translates a mesh.
inline Mesh translated(Mesh m, const Vec3& t) {
  for (Vec3& v : m.vertices) v += t;
  return m;
}

//! Exported blocks as validate_decomposition() takes them.
inline std::vector<ValidationBlock> to_validation(std::vector<ExportedBlock> blocks) {
  std::vector<ValidationBlock> out;
  for (ExportedBlock& e : blocks) {
    ValidationBlock b;
    b.mesh = std::move(e.mesh);
    b.direction = e.direction;
    b.machine_mesh = std::move(e.machine_mesh);
    b.machine_transform = e.machine_transform;
    out.push_back(std::move(b));
  }
  return out;
}

//! Issue 17's float32 regression (kitten --max-height 0.05, block 040),
//! minimal mesh: a frustum 1e-7 tall over z = 1 whose top corners round up
//! in float32 (to 1 + 1.19e-7) but corner 7 rounds down onto the base plane,
//! touching the base face: no vertex welds, the faces intersect.
inline Mesh float32_frustum() {
  Mesh m;
  m.vertices = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1},
                {0.25, 0.25, 1 + 1e-7}, {0.75, 0.25, 1 + 1e-7}, {0.75, 0.75, 1 + 1e-7}, {0.25, 0.75, 1 + 2e-8}};
  m.faces = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}};
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    m.faces.push_back({i, j, 4 + j});
    m.faces.push_back({i, 4 + j, 4 + i});
  }
  return m;
}

}  // namespace subfab::test
