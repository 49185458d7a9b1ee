// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_non_manifold_edges.h"

#include <algorithm>
#include <sstream>

#include "checks/edge_topology.h"

namespace subfab {
namespace checks_detail {

CheckResult check_non_manifold_edges(const Mesh& mesh, const EdgeTopology& topology,
                                     const CheckOptions& options) {
  std::vector<std::size_t> bad_edges;
  for (std::size_t e = 0; e < topology.num_edges(); ++e)
    if (topology.num_uses(e) > 2) bad_edges.push_back(e);
  if (bad_edges.empty())
    return passed_result("non_manifold_edges", CheckElement::Vertex,
                         "no edge is shared by more than two faces");
  std::vector<int> vertices;
  for (std::size_t e : bad_edges) vertices.push_back(topology.use(e, 0).a);
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());

  const std::size_t first = bad_edges.front();
  std::vector<int> faces;
  for (std::size_t k = 0; k < topology.num_uses(first); ++k)
    faces.push_back(topology.use(first, k).face);
  std::ostringstream message;
  message << "the mesh is not manifold: "
          << count_of(bad_edges.size(), "edge is", "edges are")
          << " shared by more than two faces, e.g. edge " << topology.use(first, 0).a << "-"
          << topology.use(first, 0).b << " (faces " << join_ids(first_ids(faces, 6))
          << (faces.size() > 6 ? ", ..." : "")
          << "); separate the parts that meet there or remove the extra faces";
  return failed_result("non_manifold_edges", CheckElement::Vertex, bad_edges.size(),
                       first_ids(vertices, options.max_examples), message.str());
}

}  // namespace checks_detail

CheckResult check_non_manifold_edges(const Mesh& mesh, const CheckOptions& options) {
  checks_detail::require_valid_indices(mesh, "non_manifold_edges");
  return checks_detail::check_non_manifold_edges(mesh, checks_detail::EdgeTopology(mesh), options);
}

}  // namespace subfab
