// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_non_manifold_vertices.h"

#include <sstream>

#include "checks/edge_topology.h"

namespace subfab {
namespace checks_detail {

namespace {
//! Corner id of vertex v in face f (3 f + slot).
int corner_of(const Mesh& mesh, int f, int v) {
  const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
  const int slot = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
  return 3 * f + slot;
}
}  // namespace

CheckResult check_non_manifold_vertices(const Mesh& mesh, const EdgeTopology& topology,
                                        const CheckOptions& options) {
  // Corners (face, vertex) at a vertex are in the same fan when their faces
  // share an edge that ends at the vertex.
  UnionFind fans(3 * mesh.num_faces());
  for (std::size_t e = 0; e < topology.num_edges(); ++e) {
    const EdgeUse& first = topology.use(e, 0);
    for (std::size_t k = 1; k < topology.num_uses(e); ++k) {
      const int f = topology.use(e, k).face;
      fans.unite(corner_of(mesh, first.face, first.a), corner_of(mesh, f, first.a));
      fans.unite(corner_of(mesh, first.face, first.b), corner_of(mesh, f, first.b));
    }
  }
  std::vector<int> fan_of_vertex(mesh.num_vertices(), -1);
  std::vector<char> pinched(mesh.num_vertices(), 0);
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    if (has_repeated_index(mesh.faces[f])) continue;
    for (std::size_t k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(mesh.faces[f][k]);
      const int fan = fans.find(static_cast<int>(3 * f + k));
      if (fan_of_vertex[v] < 0)
        fan_of_vertex[v] = fan;
      else if (fan_of_vertex[v] != fan)
        pinched[v] = 1;
    }
  }
  std::vector<int> bad;
  for (std::size_t v = 0; v < pinched.size(); ++v)
    if (pinched[v]) bad.push_back(static_cast<int>(v));
  if (bad.empty())
    return passed_result("non_manifold_vertices", CheckElement::Vertex,
                         "no pinched vertex: the faces around each vertex form one fan");
  std::ostringstream message;
  message << "the mesh is not manifold: " << count_of(bad.size(), "pinched vertex", "pinched vertices")
          << " (the faces around it form several separate fans), e.g. vertex " << bad.front()
          << "; split the vertex into one per fan or thicken the part that meets there";
  return failed_result("non_manifold_vertices", CheckElement::Vertex, bad.size(),
                       first_ids(bad, options.max_examples), message.str());
}

}  // namespace checks_detail

CheckResult check_non_manifold_vertices(const Mesh& mesh, const CheckOptions& options) {
  checks_detail::require_valid_indices(mesh, "non_manifold_vertices");
  return checks_detail::check_non_manifold_vertices(mesh, checks_detail::EdgeTopology(mesh),
                                                    options);
}

}  // namespace subfab
