// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/require_closed_solid.h"

#include <sstream>
#include <utility>

#include "checks/edge_topology.h"
#include "subfab/checks/check_components.h"
#include "subfab/checks/check_degenerate_faces.h"
#include "subfab/checks/check_duplicate_faces.h"
#include "subfab/checks/check_face_indices.h"
#include "subfab/checks/check_finite_coordinates.h"
#include "subfab/checks/check_outward_orientation.h"
#include "subfab/checks/check_self_intersections.h"
#include "subfab/core/error.h"

namespace subfab {

using namespace checks_detail;

namespace {
//! Throws the first failed check's message, naming the others briefly.
void throw_if_failed(const std::vector<CheckResult>& results) {
  const CheckResult* first = nullptr;
  std::ostringstream others;
  for (const auto& result : results) {
    if (!result.failed()) continue;
    if (!first) {
      first = &result;
      continue;
    }
    others << (others.tellp() > 0 ? ", " : "") << result.name << " (" << result.num_offending
           << ")";
  }
  if (!first) return;
  std::string message = first->message;
  if (others.tellp() > 0) message += " [also failing: " + others.str() + "]";
  throw InvalidMeshError(message);
}
}  // namespace

void require_closed_solid(Mesh& mesh, Progress* progress) {
  if (mesh.faces.empty())
    throw InvalidMeshError("the mesh has no faces; give a closed triangle mesh");
  const CheckOptions options;
  // Cheap checks first; a bad index or coordinate makes every other check meaningless.
  throw_if_failed({check_finite_coordinates(mesh, options), check_face_indices(mesh, options)});
  {
    const EdgeTopology topology(mesh);
    throw_if_failed({check_degenerate_faces(mesh, options), check_duplicate_faces(mesh, options),
                     check_boundary_edges(mesh, topology, options),
                     check_non_manifold_edges(mesh, topology, options),
                     check_non_manifold_vertices(mesh, topology, options),
                     check_consistent_orientation(mesh, topology, options)});
  }
  const CheckResult outward = check_outward_orientation(mesh, options);
  if (outward.failed()) {
    // Only a mesh that is inward as a whole is repaired (flipping every face).
    if (outward.num_offending != mesh.num_faces()) throw InvalidMeshError(outward.message);
    for (auto& face : mesh.faces) std::swap(face[1], face[2]);
    if (progress)
      progress->warn("the mesh was oriented inward (negative volume): flipped all " +
                     std::to_string(mesh.num_faces()) + " faces to point outward");
    throw_if_failed({check_outward_orientation(mesh, options)});
  }
  const CheckResult components = check_components(mesh, options);
  if (progress && components.num_groups > 1) progress->info(components.message);
  throw_if_failed({check_self_intersections(mesh, options)});
}

void require_closed_solid_result(const Mesh& mesh, const std::string& before,
                                 const std::string& after) {
  Mesh check = mesh;
  try {
    require_closed_solid(check, nullptr);
  } catch (const InvalidMeshError& e) {
    throw AlgorithmError(before + e.what() + after);
  }
}

}  // namespace subfab
