// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_duplicate_faces.h"

#include <algorithm>
#include <sstream>
#include <utility>

#include "checks/edge_topology.h"

namespace subfab {

using namespace checks_detail;

CheckResult check_duplicate_faces(const Mesh& mesh, const CheckOptions& options) {
  // (sorted corners, face id), sorted: copies of a face follow its first occurrence.
  std::vector<std::pair<Triangle, int>> keys(mesh.num_faces());
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    Triangle t = mesh.faces[f];
    std::sort(t.begin(), t.end());
    keys[f] = {t, static_cast<int>(f)};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<int> copies;
  int first_copy_original = 0;
  for (std::size_t i = 1; i < keys.size(); ++i) {
    if (keys[i].first != keys[i - 1].first) continue;
    copies.push_back(keys[i].second);
  }
  if (copies.empty())
    return passed_result("duplicate_faces", CheckElement::Face,
                         "no two faces use the same three vertices");
  std::sort(copies.begin(), copies.end());
  {
    // The face the first copy repeats: the smallest id with the same corners.
    Triangle t = mesh.faces[static_cast<std::size_t>(copies.front())];
    std::sort(t.begin(), t.end());
    first_copy_original = std::lower_bound(keys.begin(), keys.end(), std::make_pair(t, -1))->second;
  }
  std::ostringstream message;
  message << count_of(copies.size(), "face repeats", "faces repeat")
          << " the vertices of another face, e.g. face " << copies.front() << " (same as face "
          << first_copy_original << "); remove the duplicate faces";
  return failed_result("duplicate_faces", CheckElement::Face, copies.size(),
                       first_ids(copies, options.max_examples), message.str());
}

}  // namespace subfab
