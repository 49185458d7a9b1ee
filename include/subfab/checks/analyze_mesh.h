// SPDX-License-Identifier: GPL-3.0-or-later
//! \file analyze_mesh.h
//! Everything `subfab info` reports about a mesh: measures (counts, size,
//! area, volume, components, genus) and the result of every input check.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include "subfab/checks/check_result.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of analyze_mesh().
struct AnalyzeOptions {
  CheckOptions checks = {};         // shared by every check (number of example ids)
  bool self_intersections = true;   // run the self-intersection check (the slowest one)
};

//! Measures and check results of a mesh. Optional fields are empty when the
//! value is unknown or meaningless (e.g. genus of an open mesh, volume of a
//! mesh with NaN coordinates).
struct MeshReport {
  std::size_t num_vertices = 0;  // #V (as stored, referenced or not)
  std::size_t num_faces = 0;     // #F
  std::size_t num_edges = 0;     // undirected edges (faces with a repeated vertex left out)
  std::optional<BoundingBox> bbox;           // model units; empty if coordinates are not finite
  std::optional<double> diagonal;            // bounding-box diagonal, model units
  std::optional<double> average_edge_length; // model units
  std::optional<double> area;                // model units^2
  std::optional<double> volume;              // signed, model units^3; only for closed meshes
  std::size_t num_components = 0;            // connected pieces (faces linked by vertices)
  std::optional<int> genus;        // sum over components; only for closed, manifold, oriented meshes
  std::size_t num_boundary_edges = 0;
  std::size_t num_holes = 0;
  std::optional<bool> closed;             // no boundary edge
  std::optional<bool> manifold;           // no non-manifold edge or vertex
  std::optional<bool> oriented;           // consistently oriented
  std::optional<bool> outward;            // positive volume (closed, oriented meshes only)
  std::optional<bool> self_intersecting;  // empty when not checked
  std::vector<CheckResult> checks;        // every check, in the order they ran

  //! The check called `name`, or nullptr.
  const CheckResult* find(std::string_view name) const;
  //! True when no check failed.
  bool all_passed() const;
};

//! Runs every input check on `mesh` and computes its measures. Checks whose
//! preconditions fail are reported as skipped (bad indices or no faces:
//! everything else; non-finite coordinates: the geometric checks and measures; inward
//! orientation: only decided on closed, consistently oriented meshes).
//! Never throws on a bad mesh: the report says what is wrong.
//! Genus = sum over components of (2 - (V - E + F)) / 2.
//! Input validation (issue 2, item 5); no thesis section.
MeshReport analyze_mesh(const Mesh& mesh, const AnalyzeOptions& options = {});

}  // namespace subfab
