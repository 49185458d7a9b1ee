// SPDX-License-Identifier: GPL-3.0-or-later
//! \file exact_mesh.h
//! Private: the exact surface mesh the carve, merge and validate stages do
//! their booleans on (CGAL Surface_mesh on the Epeck kernel), and the
//! conversions to and from the plain double Mesh. Only .cpp files of this
//! module include it (CGAL stays out of public headers).
#pragma once

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <cstddef>
#include <string>

#include "subfab/core/error.h"
#include "subfab/geometry/height_box.h"
#include "subfab/mesh/mesh.h"

namespace subfab::detail {

using ExactKernel = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactPoint = ExactKernel::Point_3;
using ExactMesh = CGAL::Surface_mesh<ExactPoint>;
// Handles of an ExactMesh.
using VertexIndex = ExactMesh::Vertex_index;
using HalfedgeIndex = ExactMesh::Halfedge_index;
using EdgeIndex = ExactMesh::Edge_index;
using FaceIndex = ExactMesh::Face_index;

//! Lexicographic (x, y, z) order of exact points, exact: for maps keyed by
//! point and for sorting points.
struct ExactPointLess {
  bool operator()(const ExactPoint& p, const ExactPoint& q) const {
    return CGAL::compare_xyz(p, q) == CGAL::SMALLER;
  }
};

//! Builds a CGAL Surface_mesh of any point type (ExactMesh, or one on an
//! inexact kernel) from a double mesh, coordinates taken as they are:
//! vertex i and face f of `mesh` are vertex i and face f of the result.
//! \throw InvalidMeshError "face <f>" + `why_not_added` when a face cannot be
//!        added (non-manifold edge or vertex, inconsistent orientation).
template <class SurfaceMesh>
SurfaceMesh to_surface_mesh(const Mesh& mesh, const std::string& why_not_added) {
  using Size = typename SurfaceMesh::size_type;
  using Vertex = typename SurfaceMesh::Vertex_index;
  SurfaceMesh out;
  out.reserve(static_cast<Size>(mesh.num_vertices()), static_cast<Size>(3 * mesh.num_faces() / 2),
              static_cast<Size>(mesh.num_faces()));
  for (const Vec3& p : mesh.vertices)
    out.add_vertex(typename SurfaceMesh::Point(p.x(), p.y(), p.z()));
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const Triangle& t = mesh.faces[f];
    if (out.add_face(Vertex(static_cast<Size>(t[0])), Vertex(static_cast<Size>(t[1])),
                     Vertex(static_cast<Size>(t[2]))) == SurfaceMesh::null_face())
      throw InvalidMeshError("face " + std::to_string(f) + why_not_added);
  }
  return out;
}

//! Builds the exact mesh of a double mesh (coordinates are taken exactly).
//! \throw InvalidMeshError when a face cannot be added (non-manifold input).
ExactMesh to_exact(const Mesh& mesh);

//! Closed triangulated box [min, max], outward oriented.
ExactMesh box_mesh(const Box3& box);

//! What rounding an exact mesh to doubles did.
struct RoundingReport {
  std::size_t num_degenerate_faces = 0;  // faces of zero area after rounding
  std::size_t num_flipped_faces = 0;     // faces whose normal turned by > 90 degrees
};

//! Converts an exact mesh to doubles: each coordinate is rounded from its
//! exact value (deterministic, independent of evaluation history).
Mesh to_double(const ExactMesh& mesh, RoundingReport* report = nullptr);

//! Number of faces whose three corners are exactly collinear (exact
//! predicate). CGAL's corefinement must not be given such faces.
std::size_t count_degenerate_faces(const Mesh& mesh);

//! Do two (non-isolated) vertices of `mesh` lie at the same exact point?
//! Then the mesh touches itself or two of its components touch: CGAL's
//! corefinement must not be given it, and as a block it would not be a
//! 2-manifold once its vertices are merged by position.
bool has_coincident_vertices(const ExactMesh& mesh);

//! Runs a few tiny exact booleans (clip, difference, union, intersection,
//! a non-manifold one, connected components, rounding) once per thread, so
//! that CGAL's lazily created per-thread objects (the shared "zero" of each
//! lazy-exact type) are made on the normal heap, before any
//! DeterministicArena: objects made inside an arena would die with it.
//! (Defined in warm_up_exact_booleans.cpp.)
void warm_up_exact_booleans();

}  // namespace subfab::detail
