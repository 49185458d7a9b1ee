// SPDX-License-Identifier: GPL-3.0-or-later
//! \file repair_steps.h
//! Private: the steps of repair_mesh() (see include/subfab/repair/repair_mesh.h
//! for the order and what each does), on a polygon soup (steps 1-4) and on a
//! CGAL halfedge mesh (steps 5-12). Each returns its MeshRepairStep.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "subfab/repair/repair_mesh.h"

namespace subfab::detail {

using RepairKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using RepairPoint = RepairKernel::Point_3;
using RepairSurface = CGAL::Surface_mesh<RepairPoint>;

//! A triangle soup: positions and triangles (indices into points).
struct RepairSoup {
  std::vector<RepairPoint> points;
  std::vector<std::array<std::size_t, 3>> triangles;
};

//! A step called `name` with nothing found yet.
inline MeshRepairStep new_step(std::string name) {
  MeshRepairStep step;
  step.name = std::move(name);
  return step;
}

Vec3 to_vec3(const RepairPoint& p);
//! The centroid of face f of `mesh`, as an example position.
Vec3 face_centroid(const RepairSurface& mesh, RepairSurface::Face_index f);

// Steps on the soup (repair_soup.cpp).
MeshRepairStep merge_duplicate_vertices(RepairSoup& soup);
MeshRepairStep remove_repeated_corner_faces(RepairSoup& soup);
MeshRepairStep remove_duplicate_faces(RepairSoup& soup);
//! What is known of the soup before orient_soup().
enum class SoupState {
  Unknown,             // orient it (PMP::orient_polygon_soup)
  ManifoldConsistent,  // the input's exact checks passed non_manifold_edges, non_manifold_vertices and
                       // consistent_orientation, and steps 1-3 changed nothing: orienting would do nothing
};
//! Orients the soup consistently, splitting pinched vertices and edges of
//! 3+ faces, and builds the halfedge mesh: the steps "split_non_manifold"
//! and "orient". With SoupState::ManifoldConsistent only the mesh is built
//! (orient_polygon_soup was 11 of 40 s on a 1.1M-face scan).
std::vector<MeshRepairStep> orient_soup(RepairSoup& soup, RepairSurface& mesh, SoupState state);

// Steps that close the surface (close_surface.cpp).
MeshRepairStep stitch_borders(RepairSurface& mesh);
MeshRepairStep remove_small_components(RepairSurface& mesh, double min_diagonal);
MeshRepairStep remove_zero_area_faces(RepairSurface& mesh);
MeshRepairStep fill_holes(RepairSurface& mesh);
MeshRepairStep remove_flat_components(RepairSurface& mesh);
MeshRepairStep separate_pinches(RepairSurface& mesh, double distance);
//! Splits pinched vertices of the halfedge mesh (PMP::duplicate_non_manifold_vertices).
MeshRepairStep split_pinched_vertices(RepairSurface& mesh);

// Steps that make it a solid (resolve_self_intersections.cpp).
//! With `candidates`, the search for crossings is restricted to pairs of
//! those faces: the caller knows that no two other faces can cross (see
//! faces_that_may_cross in repair_mesh.cpp); null: every face.
MeshRepairStep resolve_self_intersections(RepairSurface& mesh, std::size_t max_rounds,
                                          const std::vector<RepairSurface::Face_index>* candidates = nullptr);
MeshRepairStep orient_outward(RepairSurface& mesh);

//! The mesh as a plain Mesh (vertices renumbered densely, in index order).
Mesh to_plain_mesh(const RepairSurface& mesh);

//! "(x, y, z)" with 4 significant digits.
std::string position_text(const Vec3& p);

//! The message of a step: when it applied, its count, then `found` (which
//! ends by opening the example: "... (e.g. at "), then the example position
//! ("?" when it has none) and ")"; `none` when it did not apply.
inline std::string step_message(const MeshRepairStep& step, const std::string& found, const std::string& none) {
  if (!step.applied()) return none;
  return std::to_string(step.num_found) + found + (step.where ? position_text(*step.where) : std::string("?")) + ")";
}

}  // namespace subfab::detail
