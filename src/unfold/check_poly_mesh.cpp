// SPDX-License-Identifier: GPL-3.0-or-later
//! \file check_poly_mesh.cpp
//! Exact validity check of a polygonal mesh on a lattice frame (thesis
//! Section 3.3.2: what facet deletion keeps true after every deletion):
//! closed, manifold, simple planar facets, lattice normals, no coplanar
//! neighbours, no self-intersections.
#include <string>
#include <vector>

#include "subfab/core/error.h"
#include "subfab/unfold/delete_facets.h"
#include "unfold/check_closed_manifold.h"
#include "unfold/check_no_intersections.h"
#include "unfold/exact_poly_mesh.h"
#include "unfold/merge_coplanar_neighbours.h"

namespace subfab {

using namespace unfold_detail;

std::string check_poly_mesh(const PolyMesh& poly, const Vec3& grid_origin, double grid_step) {
  ExactPolyMesh mesh;
  try {
    mesh = to_exact(poly, LatticeFrame{grid_origin, grid_step});
  } catch (const Error& e) {
    return e.what();
  }
  for (std::size_t f = 0; f < poly.facets.size(); ++f)
    if (poly.facets[f].normal < 0) return "facet " + std::to_string(f) + " has no lattice normal index";
  if (std::string r = check_closed_manifold(mesh); !r.empty()) return r;
  std::vector<int> all;
  for (std::size_t f = 0; f < mesh.facets.size(); ++f) {
    if (std::string r = check_facet_simple(mesh, int(f)); !r.empty()) return r;
    all.push_back(int(f));
  }
  if (has_coplanar_neighbours(mesh)) return "two adjacent facets are coplanar";
  return check_no_intersections(mesh, all);
}

}  // namespace subfab
