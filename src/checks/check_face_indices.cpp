// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_face_indices.h"

#include <sstream>

#include "checks/edge_topology.h"

namespace subfab {

using namespace checks_detail;

CheckResult check_face_indices(const Mesh& mesh, const CheckOptions& options) {
  const auto n = static_cast<long long>(mesh.num_vertices());
  std::vector<int> bad;
  int first_index = 0;
  for (std::size_t f = 0; f < mesh.num_faces(); ++f)
    for (int v : mesh.faces[f])
      if (v < 0 || v >= n) {
        if (bad.empty()) first_index = v;
        bad.push_back(static_cast<int>(f));
        break;
      }
  if (bad.empty())
    return passed_result("face_indices", CheckElement::Face,
                         "every face refers to existing vertices");
  std::ostringstream message;
  message << count_of(bad.size(), "face refers", "faces refer")
          << " to vertices that do not exist, e.g. face " << bad.front() << " uses vertex "
          << first_index << " (valid: 0 to " << n - 1
          << "); the file is damaged: export it again from the modelling tool";
  return failed_result("face_indices", CheckElement::Face, bad.size(),
                       first_ids(bad, options.max_examples), message.str());
}

}  // namespace subfab
