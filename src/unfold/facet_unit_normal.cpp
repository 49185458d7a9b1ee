// SPDX-License-Identifier: GPL-3.0-or-later
//! \file facet_unit_normal.cpp
//! The unit outward normal of a PolyMesh facet (thesis Section 3.3.3).
#include "unfold/facet_unit_normal.h"

#include "subfab/unfold/lattice_directions.h"

namespace subfab::unfold_detail {

Vec3 facet_unit_normal(const PolyMesh& mesh, int f) {
  const Facet& facet = mesh.facets[f];
  if (facet.normal >= 0 && facet.normal < 26) {
    const auto& d = lattice_directions()[facet.normal];
    return Vec3(d[0], d[1], d[2]).normalized();
  }
  Vec3 n = Vec3::Zero();
  const auto& l = facet.loops[0];
  for (std::size_t i = 0; i < l.size(); ++i) n += mesh.vertices[l[i]].cross(mesh.vertices[l[(i + 1) % l.size()]]);
  return n.normalized();
}

}  // namespace subfab::unfold_detail
