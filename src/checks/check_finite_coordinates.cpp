// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_finite_coordinates.h"

#include <sstream>

#include "checks/edge_topology.h"

namespace subfab {

using namespace checks_detail;

CheckResult check_finite_coordinates(const Mesh& mesh, const CheckOptions& options) {
  std::vector<int> bad;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v)
    if (!mesh.vertices[v].allFinite()) bad.push_back(static_cast<int>(v));
  if (bad.empty())
    return passed_result("finite_coordinates", CheckElement::Vertex,
                         "every vertex coordinate is a finite number");
  std::ostringstream message;
  message << count_of(bad.size(), "vertex has", "vertices have")
          << " a NaN or infinite coordinate, e.g. vertex " << bad.front()
          << "; the file is damaged: export it again from the modelling tool";
  return failed_result("finite_coordinates", CheckElement::Vertex, bad.size(),
                       first_ids(bad, options.max_examples), message.str());
}

}  // namespace subfab
