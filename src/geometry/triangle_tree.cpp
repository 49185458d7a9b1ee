// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/triangle_tree.h"

namespace subfab::detail {

TriangleTree::TriangleTree(const Mesh& mesh) {
  triangles_.reserve(mesh.num_faces());
  for (const Triangle& t : mesh.faces)
    triangles_.emplace_back(point(mesh.vertices[static_cast<std::size_t>(t[0])]),
                            point(mesh.vertices[static_cast<std::size_t>(t[1])]),
                            point(mesh.vertices[static_cast<std::size_t>(t[2])]));
  tree_.insert(triangles_.begin(), triangles_.end());
  tree_.build();
}

}  // namespace subfab::detail
