// SPDX-License-Identifier: GPL-3.0-or-later
//! \file hex_corners.h
//! Private: the corner determinants of the scaled Jacobian (Verdict's
//! definition, see scaled_jacobian.h) seen from one vertex: which corners a
//! vertex moves, their values and the gradient of a corner with respect to
//! one of its four vertices, for the optimisers of D.6.
#pragma once

#include <vector>

#include "subfab/hex/hex_mesh.h"

namespace subfab::detail {

//! One corner of one hexahedron: hexahedron index and local corner (0-7).
struct HexCorner {
  int hex;
  int corner;
};

//! Per vertex: the corners whose determinant changes when it moves (its own
//! corner and its three edge neighbours' corners in each incident hexahedron),
//! in hexahedron order.
std::vector<std::vector<HexCorner>> vertex_corners(const HexMesh& mesh);

//! Determinant of the three normalised edge vectors of corner k; -1 when an
//! edge has zero length.
double corner_determinant(const HexMesh& mesh, const HexCorner& k);

//! The determinant of corner k and its gradient with respect to the
//! position of vertex v (one of the corner's four vertices; zero otherwise).
double corner_determinant_gradient(const HexMesh& mesh, const HexCorner& k, int v, Vec3& gradient);

//! The hexahedra around a vertex v, prepared for evaluating them many times
//! while only v moves (the optimisers' line searches): the corners v does
//! not move are evaluated once; of those it moves, the edges that do not end
//! at v are normalised once, and the edges that do are normalised once per
//! evaluation for each distinct neighbour of v (6 or so instead of 96
//! normalisations for 8 hexahedra). Every corner value is computed by the
//! very operations of corner_determinant() (an edge towards v is the exact
//! negation of v's edge towards it), so the values, and sums and minima over
//! them in the same order, are bit-identical to a full evaluation.
struct VertexStar {
  //! One corner that v moves: its value is e0 . (e1 x e2), edge k being
  //! fixed[k] or, for the edges at v, +-(unit edge from v to neighbour[k]).
  struct Moved {
    Moved() {}  // no zeroing (every field a star uses is set by vertex_star)
    int neighbour[3];  // per edge: index into `neighbours` of its end other than the corner vertex (-1: fixed edge)
    double sign[3];    // +1: the corner is v, the edge leaves v; -1: the edge arrives at v
    Vec3 fixed[3];     // the fixed edges, normalised
    bool degenerate;   // a fixed edge has zero length: the corner is -1 wherever v is
  };
  std::size_t v = 0;
  const std::vector<int>* hexes = nullptr;  // v's hexahedra (HexTopology::vertex_hexes[v])
  std::vector<int> slot;                    // per (hexahedron, corner): index into `moved`, -1 if v does not move it
  std::vector<Moved> moved;
  std::vector<int> neighbours;              // the vertices joined to v by an edge of its hexahedra
  std::vector<double> fixed_min;            // per hexahedron: min(1, the corners v does not move)
  std::vector<double> fixed_exp;            // per (hexahedron, corner) v does not move: exp(-sharpness x corner)
  mutable std::vector<Vec3> units;          // per neighbour: unit edge from v (evaluate_star)
  mutable std::vector<char> zero;           // per neighbour: that edge has zero length
  mutable std::vector<double> values;       // per moved corner: its value (evaluate_star)
};

//! Every corner determinant and every edge's unit vector of a hexahedral
//! mesh, kept up to date by the optimisers (store_star after each move), so
//! that a star reads what does not change instead of computing it.
struct CornerCache {
  std::vector<double> values;  // 8 per hexahedron: corner determinants
  std::vector<Vec3> units;     // 12 per hexahedron: unit vector of edge kHexEdges[e], first corner to second
  std::vector<char> zero;      // 12 per hexahedron: that edge has zero length
};

//! The cache of `mesh` (in parallel).
CornerCache corner_cache(const HexMesh& mesh);

//! The star of v over `hexes`; fixed_exp only when sharpness > 0. With an
//! up-to-date `cache`, what v does not move is read from it instead of
//! computed.
VertexStar vertex_star(const HexMesh& mesh, const std::vector<int>& hexes, std::size_t v, double sharpness = 0,
                       const CornerCache* cache = nullptr);
//! The same into `star`, reusing its memory (a thread_local star per call
//! site keeps the optimisers' many short visits from allocating).
void build_vertex_star(VertexStar& star, const HexMesh& mesh, const std::vector<int>& hexes, std::size_t v,
                       double sharpness = 0, const CornerCache* cache = nullptr);

//! Writes the corners and edges v moves into `cache`, for v at its current
//! position.
void store_star(const HexMesh& mesh, const VertexStar& star, CornerCache& cache);

//! Per hexahedron: its scaled Jacobian from the cached corners
//! (== scaled_jacobians(mesh) when the cache is up to date).
std::vector<double> hex_qualities(const CornerCache& cache);

//! The three unit edges of the star's moved corner c, with the edges at v
//! from star.units (after evaluate_star(), or as evaluate_star() sets them);
//! false when the corner is degenerate (an edge of zero length: value -1).
inline bool star_corner_edges(const VertexStar& star, std::size_t c, Vec3 e[3]) {
  const VertexStar::Moved& m = star.moved[c];
  bool degenerate = m.degenerate;
  for (std::size_t k = 0; k < 3; ++k) {
    if (m.neighbour[k] < 0) {
      e[k] = m.fixed[k];
    } else {
      const auto s = static_cast<std::size_t>(m.neighbour[k]);
      degenerate = degenerate || star.zero[s];
      e[k] = m.sign[k] > 0 ? star.units[s] : Vec3(-star.units[s]);
    }
  }
  return !degenerate;
}

//! Fills star.values for v at its current position in `mesh`.
void evaluate_star(const HexMesh& mesh, const VertexStar& star);

//! The scaled Jacobian of the j-th hexahedron of the star, after
//! evaluate_star() (== scaled_jacobian(mesh, hexes[j])).
double star_hex_quality(const VertexStar& star, std::size_t j);

//! The smallest corner v moves, after evaluate_star() (1 if none).
double star_min_moved(const VertexStar& star);

}  // namespace subfab::detail
