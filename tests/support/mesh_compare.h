// SPDX-License-Identifier: GPL-3.0-or-later
//! Comparing meshes read from different files of the same model.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "subfab/mesh/float32.h"
#include "subfab/mesh/mesh.h"

namespace subfab::test {

//! v rounded to float32 (what binary STL and float PLY store).
inline Vec3 to_float(const Vec3& v) { return round_to_float32(v); }

//! The triangle rotated so that its smallest index comes first (same
//! orientation).
inline Triangle canonical_rotation(Triangle t) {
  while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
  return t;
}

//! Sorted list of the faces, each rotated canonically: equal for two meshes
//! with the same oriented triangles in any order and any rotation.
inline std::vector<Triangle> sorted_faces(const Mesh& mesh) {
  std::vector<Triangle> faces;
  for (const auto& t : mesh.faces) faces.push_back(canonical_rotation(t));
  std::sort(faces.begin(), faces.end());
  return faces;
}

//! The oriented triangles as corner coordinates (rotated so the
//! lexicographically smallest corner comes first), sorted: compares meshes
//! whose vertices are numbered differently (STL after welding).
inline std::vector<std::array<std::array<double, 3>, 3>> sorted_corner_triangles(const Mesh& mesh,
                                                                                bool round_to_float) {
  std::vector<std::array<std::array<double, 3>, 3>> out;
  for (const auto& t : mesh.faces) {
    std::array<std::array<double, 3>, 3> tri;
    for (int c = 0; c < 3; ++c) {
      Vec3 p = mesh.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>(c)])];
      if (round_to_float) p = to_float(p);
      tri[static_cast<std::size_t>(c)] = {p.x(), p.y(), p.z()};
    }
    while (tri[0] > tri[1] || tri[0] > tri[2]) tri = {tri[1], tri[2], tri[0]};
    out.push_back(tri);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace subfab::test
