// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_degenerate_faces.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <sstream>

#include "checks/edge_topology.h"
#include "subfab/core/parallel.h"

namespace subfab {

using namespace checks_detail;

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

Point to_point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
}  // namespace

CheckResult check_degenerate_faces(const Mesh& mesh, const CheckOptions& options) {
  const auto n = static_cast<long long>(mesh.num_vertices());
  // 0: fine or not examinable, 1: repeated index, 2: collinear corners.
  std::vector<char> kind(mesh.num_faces(), 0);
  parallel_for(
      0, mesh.num_faces(),
      [&](std::size_t f) {
        const Triangle& t = mesh.faces[f];
        for (int v : t)
          if (v < 0 || v >= n || !mesh.vertices[static_cast<std::size_t>(v)].allFinite()) return;
        if (has_repeated_index(t)) {
          kind[f] = 1;
          return;
        }
        const auto& p = mesh.vertices;
        if (CGAL::collinear(to_point(p[static_cast<std::size_t>(t[0])]),
                            to_point(p[static_cast<std::size_t>(t[1])]),
                            to_point(p[static_cast<std::size_t>(t[2])])))
          kind[f] = 2;
      },
      4096);
  std::vector<int> bad;
  std::size_t num_repeated = 0;
  for (std::size_t f = 0; f < kind.size(); ++f)
    if (kind[f] != 0) {
      bad.push_back(static_cast<int>(f));
      num_repeated += kind[f] == 1 ? 1 : 0;
    }
  if (bad.empty())
    return passed_result("degenerate_faces", CheckElement::Face, "no face has zero area");
  std::ostringstream message;
  message << count_of(bad.size(), "face has", "faces have") << " zero area ("
          << num_repeated << " with a repeated vertex, " << bad.size() - num_repeated
          << " with collinear corners), e.g. face " << bad.front()
          << "; remove or collapse the degenerate faces";
  return failed_result("degenerate_faces", CheckElement::Face, bad.size(),
                       first_ids(bad, options.max_examples), message.str());
}

}  // namespace subfab
