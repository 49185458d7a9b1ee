// SPDX-License-Identifier: GPL-3.0-or-later
//! \file edge_topology.h
//! Private machinery shared by the topological checks: the undirected edges
//! of a mesh with the faces that use them, a union-find, and small helpers
//! for the checks' messages.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "subfab/checks/check_result.h"
#include "subfab/mesh/mesh.h"

namespace subfab::checks_detail {

//! One use of an undirected edge {a, b} (a < b) by a face.
struct EdgeUse {
  int a = 0;
  int b = 0;
  int face = 0;
  bool forward = false;  // the face traverses the edge from a to b
};

//! The undirected edges of a mesh, each with the faces that use it.
//! Faces with a repeated vertex index are left out (they are reported by
//! check_degenerate_faces()). Indices must be in range.
struct EdgeTopology {
  explicit EdgeTopology(const Mesh& mesh);
  std::size_t num_edges() const { return offsets.size() - 1; }
  std::size_t num_uses(std::size_t e) const { return offsets[e + 1] - offsets[e]; }
  const EdgeUse& use(std::size_t e, std::size_t k) const { return uses[offsets[e] + k]; }

  std::vector<EdgeUse> uses;         // sorted by (a, b, face)
  std::vector<std::size_t> offsets;  // uses of edge e: [offsets[e], offsets[e + 1])
};

//! Disjoint sets over 0..n-1 (path halving, union by index: the smaller
//! index becomes the root, so results do not depend on the merge order).
class UnionFind {
 public:
  explicit UnionFind(std::size_t n);
  int find(int x);
  void unite(int x, int y);

 private:
  std::vector<int> parent_;
};

//! Connected components of the faces (linked through shared vertices).
struct FaceComponents {
  std::size_t num_components = 0;
  std::vector<int> face_component;  // #F labels, numbered in order of first face
};
FaceComponents label_face_components(const Mesh& mesh);

//! True when `face` has a repeated vertex index.
inline bool has_repeated_index(const Triangle& face) {
  return face[0] == face[1] || face[1] == face[2] || face[2] == face[0];
}

//! \throw InvalidMeshError naming `check` when a face index is out of range.
void require_valid_indices(const Mesh& mesh, std::string_view check);
//! \throw InvalidMeshError naming `check` when a coordinate is not finite.
void require_finite_coordinates(const Mesh& mesh, std::string_view check);

//! The first `max` ids of `ids` (already in ascending order).
std::vector<int> first_ids(const std::vector<int>& ids, std::size_t max);
//! "3" or "3, 7 and 9".
std::string join_ids(const std::vector<int>& ids);
//! "1 edge" / "3 edges".
std::string count_of(std::size_t n, std::string_view singular, std::string_view plural);

//! Result for a passed check.
CheckResult passed_result(std::string name, CheckElement element, std::string message);
//! Result for a failed check: `num_offending` offending elements, `examples`
//! the first few of their ids (ascending), `message` what is wrong and what
//! to do.
CheckResult failed_result(std::string name, CheckElement element, std::size_t num_offending,
                          std::vector<int> examples, std::string message);

// Overloads of the public checks that reuse an EdgeTopology (analyze_mesh).
CheckResult check_boundary_edges(const Mesh& mesh, const EdgeTopology& topology,
                                 const CheckOptions& options);
CheckResult check_non_manifold_edges(const Mesh& mesh, const EdgeTopology& topology,
                                     const CheckOptions& options);
CheckResult check_non_manifold_vertices(const Mesh& mesh, const EdgeTopology& topology,
                                        const CheckOptions& options);
CheckResult check_consistent_orientation(const Mesh& mesh, const EdgeTopology& topology,
                                         const CheckOptions& options);

}  // namespace subfab::checks_detail
