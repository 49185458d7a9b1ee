// SPDX-License-Identifier: GPL-3.0-or-later
#include "decompose/surface_deviation.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace subfab::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;

//! The listed faces of `mesh` (all if `faces` is null) as a Surface_mesh.
SurfaceMesh to_surface_mesh(const Mesh& mesh, const std::vector<int>* faces) {
  SurfaceMesh sm;
  std::unordered_map<int, SurfaceMesh::Vertex_index> map;
  auto vertex = [&](int v) {
    auto it = map.find(v);
    if (it != map.end()) return it->second;
    const Vec3& p = mesh.vertices[static_cast<std::size_t>(v)];
    const auto h = sm.add_vertex(Point(p.x(), p.y(), p.z()));
    map.emplace(v, h);
    return h;
  };
  auto add = [&](const Triangle& t) {
    const auto a = vertex(t[0]), b = vertex(t[1]), c = vertex(t[2]);
    if (sm.add_face(a, b, c) != SurfaceMesh::null_face()) return;
    // A patch can pinch at a vertex (two fans touching): this face gets its
    // own copies of the vertices (distances do not depend on connectivity).
    auto fresh = [&](int v) {
      const Vec3& p = mesh.vertices[static_cast<std::size_t>(v)];
      return sm.add_vertex(Point(p.x(), p.y(), p.z()));
    };
    sm.add_face(fresh(t[0]), fresh(t[1]), fresh(t[2]));
  };
  if (faces)
    for (int f : *faces) add(mesh.faces[static_cast<std::size_t>(f)]);
  else
    for (const Triangle& t : mesh.faces) add(t);
  return sm;
}

}  // namespace

SurfaceDeviation surface_deviation(const Mesh& input, const Mesh& reference, const Mesh& modified,
                                   const std::vector<int>& changed, double error_bound) {
  SurfaceDeviation d;
  if (changed.empty()) return d;
  namespace PMP = CGAL::Polygon_mesh_processing;
  const SurfaceMesh input_sm = to_surface_mesh(input, nullptr);
  const SurfaceMesh modified_sm = to_surface_mesh(modified, nullptr);
  const SurfaceMesh modified_patch = to_surface_mesh(modified, &changed);
  const SurfaceMesh reference_patch = to_surface_mesh(reference, &changed);
  const auto no_match = PMP::parameters::match_faces(false);
  d.hausdorff = std::max(
      PMP::bounded_error_Hausdorff_distance<CGAL::Sequential_tag>(modified_patch, input_sm, error_bound, no_match,
                                                                  no_match),
      PMP::bounded_error_Hausdorff_distance<CGAL::Sequential_tag>(reference_patch, modified_sm, error_bound,
                                                                  no_match, no_match));
  // Mean: 15 points per changed face (barycentric grid of step 1/4), area-weighted.
  using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
  Tree tree(faces(input_sm).first, faces(input_sm).second, input_sm);
  tree.accelerate_distance_queries();
  double sum = 0, area_sum = 0;
  for (int f : changed) {
    const Triangle& t = modified.faces[static_cast<std::size_t>(f)];
    const Vec3& a = modified.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = modified.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = modified.vertices[static_cast<std::size_t>(t[2])];
    const double area = 0.5 * (b - a).cross(c - a).norm();
    double face_sum = 0;
    int n = 0;
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; i + j <= 4; ++j, ++n) {
        const Vec3 p = a + (b - a) * (i / 4.0) + (c - a) * (j / 4.0);
        face_sum += std::sqrt(tree.squared_distance(Point(p.x(), p.y(), p.z())));
      }
    sum += area * face_sum / n;
    area_sum += area;
  }
  d.mean = area_sum > 0 ? sum / area_sum : 0;
  return d;
}

}  // namespace subfab::detail
