// SPDX-License-Identifier: GPL-3.0-or-later
//! \file exact_poly_mesh.h
//! Private: a PolyMesh with exact rational vertex coordinates (in lattice
//! units), on which facet deletion (thesis Section 3.3.2) and the
//! polygonal-mesh checks decide validity exactly. The checks and clean-ups
//! have their own headers: check_closed_manifold.h (closedness,
//! manifoldness), check_no_intersections.h (simple facets, facet-facet
//! intersection), merge_coplanar_neighbours.h (coplanar neighbours).
//!
//! All facet normals are lattice directions n in {-1, 0, 1}^3, so a facet's
//! plane is n.x = c with integer n; with vertices at rational lattice
//! coordinates every construction (plane-plane-plane intersection) stays
//! rational and every decision is exact.
#pragma once

#include <CGAL/Gmpq.h>

#include <array>
#include <vector>

#include "subfab/unfold/poly_mesh.h"

namespace subfab::unfold_detail {

using Q = CGAL::Gmpq;

struct QVec {
  Q x, y, z;
  const Q& operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  Q& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};

QVec operator+(const QVec& a, const QVec& b);
QVec operator-(const QVec& a, const QVec& b);
QVec operator*(const Q& s, const QVec& a);
bool operator==(const QVec& a, const QVec& b);
Q dot(const QVec& a, const QVec& b);
QVec cross(const QVec& a, const QVec& b);
QVec to_qvec(const std::array<int, 3>& v);
bool is_zero(const QVec& a);

//! One facet: loops of vertex ids (outer CCW from outside, holes CW), the
//! lattice normal (integer) and its index, and the plane constant c of n.x = c.
struct QFacet {
  std::vector<std::vector<int>> loops;
  int normal_index = -1;
  std::array<int, 3> normal{0, 0, 0};
  Q offset;  // n . x for every point x of the facet
  bool alive = true;
};

//! How vertex coordinates map between model units and exact lattice units:
//! model = origin + step * q, with q a rational whose denominator divides 24.
//! step == 0: model coordinates are taken as exact rationals (origin ignored).
struct LatticeFrame {
  Vec3 origin = Vec3::Zero();
  double step = 0;
};

struct ExactPolyMesh {
  std::vector<QVec> points;
  std::vector<Vec3> approx;  // double approximations (model units), for filters
  std::vector<QFacet> facets;
  LatticeFrame frame;
};

//! Converts a PolyMesh (throws InvalidArgumentError when a vertex is not on
//! the 1/24 sub-lattice of the frame, or a facet normal is not a lattice
//! direction, or a facet is not exactly planar).
ExactPolyMesh to_exact(const PolyMesh& mesh, const LatticeFrame& frame);
//! Back to doubles, dropping dead facets and unused vertices.
PolyMesh to_poly_mesh(const ExactPolyMesh& mesh);
//! Model-unit position of an exact point.
Vec3 to_model(const QVec& q, const LatticeFrame& frame);

//! Adds a point (no deduplication); returns its id.
int add_point(ExactPolyMesh& mesh, const QVec& q);

//! The axis a facet's 2-D projection drops: its normal's first non-zero one.
inline int drop_axis(const QFacet& f) {
  for (int k = 0; k < 3; ++k)
    if (f.normal[k] != 0) return k;
  return 2;
}

//! A point of a facet's plane projected along axis k: (p[k+1], p[k+2]).
struct P2 {
  Q u, v;
};

inline P2 project(const QVec& p, int k) { return {p[(k + 1) % 3], p[(k + 2) % 3]}; }

//! Twice the signed area of a loop, projected along the facet normal's first
//! non-zero axis, with the sign of "counter-clockwise seen from the normal".
Q loop_area2(const ExactPolyMesh& mesh, const QFacet& facet, const std::vector<int>& loop);

//! Exact area of a facet in model units^2 (approximate: double).
double facet_area(const ExactPolyMesh& mesh, int f);

}  // namespace subfab::unfold_detail
