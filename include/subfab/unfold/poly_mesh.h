// SPDX-License-Identifier: GPL-3.0-or-later
//! \file poly_mesh.h
//! A closed polygonal surface made of planar facets: what the unfoldable
//! simplification (thesis Chapter 3) produces and unfolds. Each facet is a
//! planar region bounded by one outer loop and possibly hole loops.
#pragma once

#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! One planar facet.
//! - loops[0]: outer boundary, counter-clockwise seen from outside the solid
//!   (i.e. seen from the side the normal points to);
//! - loops[1..]: holes, clockwise seen from outside.
//! - normal: index into lattice_directions() (the facet's outward normal is
//!   that direction, normalised), or -1 when not a lattice direction.
struct Facet {
  std::vector<std::vector<int>> loops;
  int normal = -1;
};

//! Polygonal mesh: shared vertices, facets referring to them.
//! Adjacent facets share whole edges (vertex pairs), so the surface is
//! closed when every directed edge (a, b) of a loop has exactly one
//! opposite (b, a) in another loop.
struct PolyMesh {
  std::vector<Vec3> vertices;
  std::vector<Facet> facets;

  std::size_t num_vertices() const { return vertices.size(); }
  std::size_t num_facets() const { return facets.size(); }
};

}  // namespace subfab
