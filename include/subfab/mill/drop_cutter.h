// SPDX-License-Identifier: GPL-3.0-or-later
//! \file drop_cutter.h
//! Drop-cutter: the lowest height at which a vertical tool, centred above a
//! point (x, y), touches a triangle mesh (and a floor) from above. It is the
//! tool position of every toolpath `subfab mill` writes, so the tool never
//! cuts below the mesh's top surface.
//!
//! Per triangle the contact is the highest of three cases, each exact in
//! closed form (double precision):
//!  - vertex: the tool's lower surface resting on a corner;
//!  - edge: resting on the segment (ball: the sphere tangent to the edge's
//!    line inside the segment, solved in the edge's vertical plane; flat:
//!    the bottom disk's rim crossing the edge);
//!  - facet: resting on the triangle's interior (the tangent point of the
//!    sphere, or the uphill rim point of the disk, inside the triangle).
//! The mesh's triangles are kept in a uniform grid over the xy plane, so a
//! query only looks at triangles whose xy bounding box meets the tool's
//! footprint. Plain Eigen and a flat array of cells: no CGAL tree is needed
//! for a 2D range over a few thousand triangles.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "subfab/mesh/mesh.h"
#include "subfab/mill/tool.h"

namespace subfab {

//! A triangle mesh binned in a uniform 2D grid of its xy bounding boxes.
class TriangleGrid {
 public:
  //! \param mesh      triangles (any units; queries use the same units)
  //! \param cell_size grid spacing (> 0); about the tool radius is a good choice
  TriangleGrid(const Mesh& mesh, double cell_size);

  //! Appends to `out` the ids of the triangles whose xy bounding box meets the
  //! box [x0, x1] x [y0, y1], each once (in no set order: drop_cutter()
  //! takes a maximum, which does not depend on it).
  void query(double x0, double y0, double x1, double y1, std::vector<int>& out) const;

  struct Tri {
    Vec3 a, b, c;
    Vec3 normal;  // unit normal (zero for a degenerate triangle)
    double top;   // highest z of its corners
  };
  const std::vector<Tri>& triangles() const { return tris_; }

 private:
  std::vector<Tri> tris_;
  std::vector<std::vector<int>> cells_;
  double x0_ = 0, y0_ = 0, cell_ = 1;
  int nx_ = 0, ny_ = 0;
};

//! Height of the tool's reference point (lowest point: ball tip, flat disk)
//! when it is lowered along -z above (x, y) until it touches the mesh or the
//! plane z = floor, whichever comes first: the maximum over the triangles
//! within reach of their vertex, edge and facet contact heights, and `floor`.
//! Thread-safe (the grid is read only).
double drop_cutter(const TriangleGrid& grid, const Tool& tool, double x, double y, double floor = 0.0);

}  // namespace subfab
