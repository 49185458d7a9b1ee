// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_boundary_edges.h"

#include <algorithm>
#include <sstream>

#include "checks/edge_topology.h"

namespace subfab {
namespace checks_detail {

CheckResult check_boundary_edges(const Mesh& mesh, const EdgeTopology& topology,
                                 const CheckOptions& options) {
  // Holes: connected sets of boundary edges (joined at their vertices).
  UnionFind holes(mesh.num_vertices());
  std::vector<int> boundary_vertices;
  std::size_t num_boundary = 0;
  for (std::size_t e = 0; e < topology.num_edges(); ++e) {
    if (topology.num_uses(e) != 1) continue;
    const EdgeUse& use = topology.use(e, 0);
    holes.unite(use.a, use.b);
    boundary_vertices.push_back(use.a);
    boundary_vertices.push_back(use.b);
    ++num_boundary;
  }
  if (num_boundary == 0)
    return passed_result("boundary_edges", CheckElement::Vertex,
                         "closed: every edge is shared by two faces or more");
  // One example per hole: its smallest vertex id (the union-find root).
  std::vector<int> roots;
  for (int v : boundary_vertices) roots.push_back(holes.find(v));
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());

  std::ostringstream message;
  message << "the mesh is not closed: " << count_of(num_boundary, "boundary edge", "boundary edges")
          << " in " << count_of(roots.size(), "hole", "holes") << ", e.g. around vertex "
          << roots.front() << "; close the holes before decomposing";
  CheckResult result = failed_result("boundary_edges", CheckElement::Vertex, num_boundary,
                                     first_ids(roots, options.max_examples), message.str());
  result.num_groups = roots.size();
  return result;
}

}  // namespace checks_detail

CheckResult check_boundary_edges(const Mesh& mesh, const CheckOptions& options) {
  checks_detail::require_valid_indices(mesh, "boundary_edges");
  return checks_detail::check_boundary_edges(mesh, checks_detail::EdgeTopology(mesh), options);
}

}  // namespace subfab
