// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/surface_deviation.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <functional>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace subfab::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;

//! The listed faces of `mesh` (all if `faces` is null) as a Surface_mesh.
SurfaceMesh to_surface_mesh(const Mesh& mesh, const std::vector<int>* faces) {
  SurfaceMesh sm;
  append_distance_patch(sm, mesh, faces);
  return sm;
}

}  // namespace

void append_distance_patch(DistanceMesh& out, const Mesh& mesh, const std::vector<int>* faces) {
  std::unordered_map<int, DistanceMesh::Vertex_index> map;
  auto point = [&](int v) {
    const Vec3& p = mesh.vertices[static_cast<std::size_t>(v)];
    return Point(p.x(), p.y(), p.z());
  };
  auto vertex = [&](int v) {
    auto it = map.find(v);
    if (it != map.end()) return it->second;
    const auto h = out.add_vertex(point(v));
    map.emplace(v, h);
    return h;
  };
  auto add = [&](const Triangle& t) {
    const auto a = vertex(t[0]), b = vertex(t[1]), c = vertex(t[2]);
    if (out.add_face(a, b, c) != DistanceMesh::null_face()) return;
    out.add_face(out.add_vertex(point(t[0])), out.add_vertex(point(t[1])), out.add_vertex(point(t[2])));
  };
  if (faces)
    for (int f : *faces) add(mesh.faces[static_cast<std::size_t>(f)]);
  else
    for (const Triangle& t : mesh.faces) add(t);
}

double one_sided_hausdorff(const DistanceMesh& from, const DistanceMesh& to, double error) {
  if (from.number_of_faces() == 0) return 0.0;
  if (to.number_of_faces() == 0) return std::numeric_limits<double>::infinity();
  namespace PMP = CGAL::Polygon_mesh_processing;
  const auto no_match = PMP::parameters::match_faces(false);
  return PMP::bounded_error_Hausdorff_distance<CGAL::Sequential_tag>(from, to, error, no_match, no_match);
}

Mesh clipped_faces(const Mesh& mesh, const std::vector<int>& faces, const BoundingBox& box) {
  Mesh out;
  std::vector<Vec3> poly, next;
  for (int f : faces) {
    poly.clear();
    for (int v : mesh.faces[static_cast<std::size_t>(f)]) poly.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
    for (int k = 0; k < 3 && !poly.empty(); ++k)
      for (int side = 0; side < 2 && !poly.empty(); ++side) {
        // keep sgn * (p[k] - bound) <= 0
        const double bound = side == 0 ? box.max[k] : box.min[k];
        const double sgn = side == 0 ? 1.0 : -1.0;
        next.clear();
        for (std::size_t i = 0; i < poly.size(); ++i) {
          const Vec3& a = poly[i];
          const Vec3& b = poly[(i + 1) % poly.size()];
          const double da = sgn * (a[k] - bound), db = sgn * (b[k] - bound);
          if (da <= 0) next.push_back(a);
          if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
            Vec3 c = a + (b - a) * (da / (da - db));
            c[k] = bound;
            next.push_back(c);
          }
        }
        poly.swap(next);
      }
    if (poly.size() < 3) continue;
    // fanned from the first corner; a fan triangle of zero area (three
    // corners on a line) holds no point its neighbours do not: left out
    const int base = static_cast<int>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), poly.begin(), poly.end());
    for (std::size_t i = 1; i + 1 < poly.size(); ++i)
      if ((poly[i] - poly[0]).cross(poly[i + 1] - poly[0]).squaredNorm() > 0)
        out.faces.push_back({base, base + static_cast<int>(i), base + static_cast<int>(i) + 1});
  }
  return out;
}

SurfaceDeviation surface_deviation(const Mesh& input, const Mesh& reference, const Mesh& modified,
                                   const std::vector<int>& changed, double error_bound) {
  if (&reference == &input || (reference.vertices == input.vertices && reference.faces == input.faces))
    return surface_deviation(input, changed, modified, changed, error_bound);
  SurfaceDeviation d = surface_deviation(input, std::vector<int>{}, modified, changed, error_bound);
  namespace PMP = CGAL::Polygon_mesh_processing;
  const auto no_match = PMP::parameters::match_faces(false);
  if (!changed.empty())
    d.hausdorff = std::max(d.hausdorff, PMP::bounded_error_Hausdorff_distance<CGAL::Sequential_tag>(
                                            to_surface_mesh(reference, &changed), to_surface_mesh(modified, nullptr),
                                            error_bound, no_match, no_match));
  return d;
}

SurfaceDeviation surface_deviation(const Mesh& input, const std::vector<int>& changed_input, const Mesh& modified,
                                   const std::vector<int>& changed_modified, double error_bound) {
  SurfaceDeviation d;
  if (changed_modified.empty() && changed_input.empty()) return d;
  namespace PMP = CGAL::Polygon_mesh_processing;
  const SurfaceMesh input_sm = to_surface_mesh(input, nullptr);
  const auto no_match = PMP::parameters::match_faces(false);
  if (!changed_modified.empty())
    d.hausdorff = PMP::bounded_error_Hausdorff_distance<CGAL::Sequential_tag>(
        to_surface_mesh(modified, &changed_modified), input_sm, error_bound, no_match, no_match);
  if (!changed_input.empty())
    d.hausdorff = std::max(d.hausdorff, PMP::bounded_error_Hausdorff_distance<CGAL::Sequential_tag>(
                                            to_surface_mesh(input, &changed_input), to_surface_mesh(modified, nullptr),
                                            error_bound, no_match, no_match));
  // Mean: 15 points per changed face (barycentric grid of step 1/4), area-weighted.
  using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
  Tree tree(faces(input_sm).first, faces(input_sm).second, input_sm);
  tree.accelerate_distance_queries();
  double sum = 0, area_sum = 0;
  for (int f : changed_modified) {
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

std::vector<int> faces_not_in(const Mesh& a, const Mesh& b) {
  // A face as its corner positions, rotated to start at the smallest one.
  using Key = std::array<double, 9>;
  const auto key = [](const Mesh& m, const Triangle& t) {
    std::array<Vec3, 3> p{m.vertices[static_cast<std::size_t>(t[0])], m.vertices[static_cast<std::size_t>(t[1])],
                          m.vertices[static_cast<std::size_t>(t[2])]};
    const auto less = [](const Vec3& x, const Vec3& y) {
      return std::lexicographical_compare(x.data(), x.data() + 3, y.data(), y.data() + 3);
    };
    int first = 0;
    for (int i = 1; i < 3; ++i)
      if (less(p[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(first)])) first = i;
    Key k{};
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 3; ++c) k[static_cast<std::size_t>(3 * i + c)] = p[static_cast<std::size_t>((first + i) % 3)][c];
    return k;
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::size_t h = 0;
      for (double x : k) h = h * 1000003u ^ std::hash<double>{}(x);
      return h;
    }
  };
  std::unordered_set<Key, KeyHash> in_b;
  in_b.reserve(b.faces.size());
  for (const Triangle& t : b.faces) in_b.insert(key(b, t));
  std::vector<int> out;
  for (std::size_t f = 0; f < a.faces.size(); ++f)
    if (!in_b.count(key(a, a.faces[f]))) out.push_back(static_cast<int>(f));
  return out;
}

}  // namespace subfab::detail
