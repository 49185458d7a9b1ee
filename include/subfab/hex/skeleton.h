// SPDX-License-Identifier: GPL-3.0-or-later
//! \file skeleton.h
//! The curve-skeleton the hexahedral mesher works from (thesis Appendix D):
//! a graph of nodes, each a point with the radius of its maximal sphere, and
//! the arcs (chains of degree-2 nodes) between branching and terminal nodes.
#pragma once

#include <cstddef>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! A curve-skeleton: #N nodes with positions (model units), radii (model
//! units, > 0) and symmetric adjacency lists (0-based node indices, no
//! self-loops, no repeated neighbour).
struct Skeleton {
  std::vector<Vec3> points;
  std::vector<double> radii;
  std::vector<std::vector<int>> neighbors;

  std::size_t num_nodes() const { return points.size(); }
  std::size_t num_edges() const;
  //! Adds node (p, r) and returns its index.
  int add_node(const Vec3& p, double r);
  //! Adds the undirected edge a-b (nothing if it exists or a == b).
  void add_edge(int a, int b);
};

//! A maximal chain of the skeleton: `nodes` runs from a branching or
//! terminal node (degree != 2) through degree-2 nodes to another (or the
//! same) such node. A connected component that is a pure cycle (all nodes of
//! degree 2) is one arc that starts and ends at its lowest-index node
//! (front() == back()) with `closed` set.
struct SkeletonArc {
  std::vector<int> nodes;
  bool closed = false;  // pure cycle with no branching or terminal node
};

//! The arcs of `skeleton`, in a deterministic order (by first node, then by
//! the neighbour they leave it through). Isolated nodes give no arc.
std::vector<SkeletonArc> skeleton_arcs(const Skeleton& skeleton);

//! Length of the polyline through the arc's nodes.
double arc_length(const Skeleton& skeleton, const SkeletonArc& arc);

//! Checks sizes, finite coordinates, positive radii, index ranges, symmetry,
//! no self-loops or repeated neighbours.
//! \throw InvalidArgumentError naming the first offending node.
void check_skeleton(const Skeleton& skeleton);

//! Number of connected components of the skeleton graph with at least one node.
std::size_t num_skeleton_components(const Skeleton& skeleton);

}  // namespace subfab
