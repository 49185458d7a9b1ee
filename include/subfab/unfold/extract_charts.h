// SPDX-License-Identifier: GPL-3.0-or-later
//! \file extract_charts.h
//! Stage 3 of the unfoldable simplification (thesis Section 3.3.1: "we
//! consider adjacent triangles with the same normal as a unique polygonal
//! facet"): merge edge-adjacent triangles with the same lattice normal into
//! planar polygonal facets (charts) and return them as a PolyMesh.
#pragma once

#include <vector>

#include "subfab/core/progress.h"
#include "subfab/mesh/mesh.h"
#include "subfab/unfold/poly_mesh.h"

namespace subfab {

//! Options of extract_charts().
struct ChartOptions {
  bool remove_straight_vertices = true;  // drop vertices touched by exactly two facets (they lie
                                         // on the straight line where the two planes meet); both
                                         // facets drop them, so shared edges stay shared
  Progress* progress = nullptr;          // optional progress receiver
};

//! Result of extract_charts().
struct Charts {
  PolyMesh poly;                // one facet per chart; vertices: those on some facet boundary
  std::vector<int> face_chart;  // per input triangle: its facet in poly
};

//! Merges triangles into charts: two triangles sharing an edge are in the
//! same chart when their normal indices are equal (sharing an edge and a
//! normal, they share the plane). Each chart becomes a Facet: loops[0] its
//! outer boundary, counter-clockwise seen from outside, then its holes
//! (clockwise); a vertex where a chart touches itself is split between the
//! loops by walking around the vertex inside the chart.
//! \param mesh    closed, 2-manifold, outward-oriented triangle mesh (e.g. marching_cubes()).
//! \param normals per triangle: index into lattice_directions().
//! \return the PolyMesh (facets in order of their smallest triangle: deterministic).
//! \throw InvalidArgumentError when sizes differ; AlgorithmError when the
//!        mesh is not closed and 2-manifold or a chart is not a planar region
//!        with one outer boundary.
Charts extract_charts(const Mesh& mesh, const std::vector<int>& normals, const ChartOptions& options = {});

//! Number of directed loop edges (a, b) of `poly` that do not have exactly one
//! opposite (b, a) elsewhere: 0 for a closed, consistently oriented PolyMesh.
std::size_t count_unpaired_edges(const PolyMesh& poly);

}  // namespace subfab
