// SPDX-License-Identifier: GPL-3.0-or-later
//! \file hex_splitter.h
//! Private: the regular 2 x 2 x 2 split of hexahedra (or along some of their axes: layer_keeping_axes()) into a new mesh, with
//! edge midpoints and face centres shared between neighbours (keyed by the
//! old vertex indices), so that the hexahedra split in one pass stay
//! conforming with each other and with any template that asks for the same
//! midpoints (the cone templates of D.5, refine_hex_mesh()).
#pragma once

#include <array>
#include <map>
#include <utility>

#include "subfab/hex/hex_mesh.h"

namespace subfab::detail {

class HexSplitter {
 public:
  //! `out` starts as a copy of `in`'s vertices (old vertices keep their
  //! indices); new vertices are appended.
  HexSplitter(const HexMesh& in, HexMesh& out);
  //! The midpoint of edge a-b (created once).
  int edge(int a, int b);
  //! The centre of the quad a, b, c, d (any order; created once).
  int face(int a, int b, int c, int d);
  //! Appends the 8 children of h to `out` (trilinear positions).
  void split(const Hex& h);
  //! Splits h in two along each local axis i (0: corner 0 -> 1, 1: 0 -> 3,
  //! 2: 0 -> 4) with axes[i] set, 1 to 8 children (in the order of split(),
  //! i fastest), positions trilinear; all three set is split(h).
  void split(const Hex& h, const std::array<bool, 3>& axes);

 private:
  const HexMesh& in_;
  HexMesh& out_;
  std::map<std::pair<int, int>, int> edge_mid_;
  std::map<std::array<int, 4>, int> face_mid_;
  int add(const Vec3& p);
};

}  // namespace subfab::detail
