// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_components.h"

#include <sstream>

#include "checks/edge_topology.h"

namespace subfab {

using namespace checks_detail;

CheckResult check_components(const Mesh& mesh, const CheckOptions& options) {
  require_valid_indices(mesh, "components");
  const FaceComponents components = label_face_components(mesh);
  std::vector<int> first_face(components.num_components, -1);
  std::vector<std::size_t> num_faces(components.num_components, 0);
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const auto c = static_cast<std::size_t>(components.face_component[f]);
    if (first_face[c] < 0) first_face[c] = static_cast<int>(f);
    ++num_faces[c];
  }
  CheckResult result;
  result.name = "components";
  result.status = CheckStatus::Passed;
  result.element = CheckElement::Face;
  result.num_groups = components.num_components;
  result.examples = first_ids(first_face, options.max_examples);
  std::ostringstream message;
  message << count_of(components.num_components, "connected component", "connected components");
  if (components.num_components > 1) {
    message << " (faces:";
    for (std::size_t c = 0; c < std::min<std::size_t>(num_faces.size(), options.max_examples); ++c)
      message << " " << num_faces[c];
    if (num_faces.size() > options.max_examples) message << " ...";
    message << "); allowed, each is a separate solid";
  }
  result.message = message.str();
  return result;
}

}  // namespace subfab
