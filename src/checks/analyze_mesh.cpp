// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/analyze_mesh.h"

#include <string>

#include "checks/edge_topology.h"
#include "subfab/checks/check_components.h"
#include "subfab/checks/check_degenerate_faces.h"
#include "subfab/checks/check_duplicate_faces.h"
#include "subfab/checks/check_face_indices.h"
#include "subfab/checks/check_finite_coordinates.h"
#include "subfab/checks/check_outward_orientation.h"
#include "subfab/checks/check_self_intersections.h"

namespace subfab {

using namespace checks_detail;

const CheckResult* MeshReport::find(std::string_view name) const {
  for (const auto& check : checks)
    if (check.name == name) return &check;
  return nullptr;
}

bool MeshReport::all_passed() const {
  for (const auto& check : checks)
    if (check.failed()) return false;
  return true;
}

namespace {

CheckResult skipped(std::string name, std::string reason) {
  CheckResult result;
  result.name = std::move(name);
  result.status = CheckStatus::Skipped;
  result.message = "not checked: " + std::move(reason);
  return result;
}

//! Sum over components of (2 - chi) / 2, or nothing if some chi is odd.
std::optional<int> total_genus(const Mesh& mesh, const EdgeTopology& topology) {
  const FaceComponents components = label_face_components(mesh);
  std::vector<long long> chi(components.num_components, 0);
  std::vector<int> vertex_component(mesh.num_vertices(), -1);
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const int c = components.face_component[f];
    chi[static_cast<std::size_t>(c)] += 1;
    for (int v : mesh.faces[f]) {
      if (vertex_component[static_cast<std::size_t>(v)] < 0) {
        vertex_component[static_cast<std::size_t>(v)] = c;
        chi[static_cast<std::size_t>(c)] += 1;
      }
    }
  }
  for (std::size_t e = 0; e < topology.num_edges(); ++e)
    chi[static_cast<std::size_t>(vertex_component[static_cast<std::size_t>(topology.use(e, 0).a)])] -= 1;
  long long genus = 0;
  for (long long x : chi) {
    if ((2 - x) % 2 != 0 || x > 2) return std::nullopt;
    genus += (2 - x) / 2;
  }
  return static_cast<int>(genus);
}

}  // namespace

MeshReport analyze_mesh(const Mesh& mesh, const AnalyzeOptions& options) {
  const CheckOptions& o = options.checks;
  MeshReport report;
  report.num_vertices = mesh.num_vertices();
  report.num_faces = mesh.num_faces();

  report.checks.push_back(check_finite_coordinates(mesh, o));
  report.checks.push_back(check_face_indices(mesh, o));
  const bool finite = report.checks[0].passed();
  const bool indices = report.checks[1].passed();
  if (!indices || mesh.faces.empty()) {
    const char* reason =
        indices ? "the mesh has no faces" : "some faces refer to vertices that do not exist";
    for (const char* name : {"degenerate_faces", "duplicate_faces", "boundary_edges",
                             "non_manifold_edges", "non_manifold_vertices",
                             "consistent_orientation", "outward_orientation", "components",
                             "self_intersections"})
      report.checks.push_back(skipped(name, reason));
    return report;
  }

  const EdgeTopology topology(mesh);
  report.num_edges = topology.num_edges();
  report.checks.push_back(check_degenerate_faces(mesh, o));
  const bool no_repeated_index = [&] {
    for (const auto& t : mesh.faces)
      if (has_repeated_index(t)) return false;
    return true;
  }();
  report.checks.push_back(check_duplicate_faces(mesh, o));
  report.checks.push_back(check_boundary_edges(mesh, topology, o));
  const CheckResult& boundary = report.checks.back();
  report.num_boundary_edges = boundary.num_offending;
  report.num_holes = boundary.num_groups;
  report.closed = boundary.passed();
  report.checks.push_back(check_non_manifold_edges(mesh, topology, o));
  const bool manifold_edges = report.checks.back().passed();
  report.checks.push_back(check_non_manifold_vertices(mesh, topology, o));
  report.manifold = manifold_edges && report.checks.back().passed();
  report.checks.push_back(check_consistent_orientation(mesh, topology, o));
  report.oriented = report.checks.back().passed();

  if (!finite)
    report.checks.push_back(skipped("outward_orientation", "some coordinates are not finite"));
  else if (!*report.closed)
    report.checks.push_back(skipped("outward_orientation", "the mesh is not closed"));
  else if (!*report.oriented)
    report.checks.push_back(
        skipped("outward_orientation", "the faces are not consistently oriented"));
  else {
    report.checks.push_back(check_outward_orientation(mesh, o));
    report.outward = report.checks.back().passed();
  }

  report.checks.push_back(check_components(mesh, o));
  report.num_components = report.checks.back().num_groups;

  if (!finite) {
    report.checks.push_back(skipped("self_intersections", "some coordinates are not finite"));
  } else if (!options.self_intersections) {
    report.checks.push_back(skipped("self_intersections", "switched off"));
  } else {
    report.checks.push_back(check_self_intersections(mesh, o));
    report.self_intersecting = !report.checks.back().passed();
  }

  if (finite) {
    report.bbox = bounding_box(mesh);
    report.diagonal = report.bbox->diagonal();
    report.average_edge_length = average_edge_length(mesh);
    report.area = surface_area(mesh);
    if (*report.closed) report.volume = signed_volume(mesh);
  }
  if (*report.closed && *report.manifold && *report.oriented && no_repeated_index)
    report.genus = total_genus(mesh, topology);
  return report;
}

}  // namespace subfab
