// SPDX-License-Identifier: GPL-3.0-or-later
//! \file triangle_tree.h
//! Private: a mesh's faces as CGAL triangles (EPICK kernel) under an AABB
//! tree, the one way the systems build one for distance queries and ray
//! casts (validate's OutsideDistance, decompose's FillScreen, the sampled
//! Hausdorff distance).
#pragma once

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! The faces of a mesh, in order (face f is triangles()[f], degenerate ones
//! included), and an AABB tree over them whose primitive ids are iterators
//! into triangles() (id - triangles().begin() is the face index).
class TriangleTree {
 public:
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Triangle3 = Kernel::Triangle_3;
  using Iterator = std::vector<Triangle3>::const_iterator;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_triangle_primitive<Kernel, Iterator>>>;

  //! Copies the faces of `mesh` and builds the tree (not its distance
  //! accelerator: see accelerate_distance_queries()).
  explicit TriangleTree(const Mesh& mesh);
  TriangleTree(const TriangleTree&) = delete;  // the tree points into triangles_
  TriangleTree& operator=(const TriangleTree&) = delete;

  //! Builds the search structure of closest-point queries now (CGAL builds
  //! it lazily on the first one, which must then not run concurrently).
  void accelerate_distance_queries() { tree_.accelerate_distance_queries(); }

  const std::vector<Triangle3>& triangles() const { return triangles_; }
  const Tree& tree() const { return tree_; }

  static Kernel::Point_3 point(const Vec3& p) { return Kernel::Point_3(p.x(), p.y(), p.z()); }

 private:
  std::vector<Triangle3> triangles_;
  Tree tree_;
};

}  // namespace subfab::detail
