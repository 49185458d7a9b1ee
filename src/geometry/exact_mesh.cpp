// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/exact_mesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <vector>

namespace subfab::detail {

ExactMesh to_exact(const Mesh& mesh) {
  return to_surface_mesh<ExactMesh>(
      mesh,
      " cannot be added to a halfedge mesh (non-manifold edge or vertex, or "
      "inconsistent orientation); repair the mesh first");
}

ExactMesh box_mesh(const Box3& box) {
  ExactMesh out;
  std::array<ExactMesh::Vertex_index, 8> v;
  for (int i = 0; i < 8; ++i) {
    const double x = (i & 1) ? box.max.x() : box.min.x();
    const double y = (i & 2) ? box.max.y() : box.min.y();
    const double z = (i & 4) ? box.max.z() : box.min.z();
    v[static_cast<std::size_t>(i)] = out.add_vertex(ExactPoint(x, y, z));
  }
  // Outward-oriented quads (counter-clockwise seen from outside), split in two.
  static constexpr int kQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                       {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : kQuads) {
    out.add_face(v[q[0]], v[q[1]], v[q[2]]);
    out.add_face(v[q[0]], v[q[2]], v[q[3]]);
  }
  return out;
}

namespace {
double round_exact(const ExactKernel::FT& x) { return CGAL::to_double(CGAL::exact(x)); }
}  // namespace

Mesh to_double(const ExactMesh& mesh, RoundingReport* report) {
  Mesh out;
  out.vertices.reserve(mesh.number_of_vertices());
  out.faces.reserve(mesh.number_of_faces());
  std::vector<int> index(mesh.num_vertices(), -1);
  for (auto v : mesh.vertices()) {
    const ExactPoint& p = mesh.point(v);
    index[v.idx()] = static_cast<int>(out.vertices.size());
    out.vertices.emplace_back(round_exact(p.x()), round_exact(p.y()), round_exact(p.z()));
  }
  for (auto f : mesh.faces()) {
    Triangle t{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      if (k < 3) t[static_cast<std::size_t>(k)] = index[v.idx()];
      ++k;
    }
    out.faces.push_back(t);
    if (report) {
      const Vec3 n = face_normal_scaled(out, out.faces.size() - 1);
      auto h = mesh.halfedge(f);
      const ExactPoint& a = mesh.point(mesh.source(h));
      const ExactPoint& b = mesh.point(mesh.target(h));
      const ExactPoint& c = mesh.point(mesh.target(mesh.next(h)));
      const auto en = CGAL::cross_product(b - a, c - a);
      const Vec3 approx(CGAL::to_double(en.x()), CGAL::to_double(en.y()), CGAL::to_double(en.z()));
      if (n.squaredNorm() == 0.0)
        ++report->num_degenerate_faces;
      else if (n.dot(approx) <= 0.0)
        ++report->num_flipped_faces;
    }
  }
  return out;
}

std::size_t count_degenerate_faces(const Mesh& mesh) {
  using P = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
  std::size_t n = 0;
  for (const Triangle& t : mesh.faces) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    if (CGAL::collinear(P(a.x(), a.y(), a.z()), P(b.x(), b.y(), b.z()), P(c.x(), c.y(), c.z()))) ++n;
  }
  return n;
}

bool has_coincident_vertices(const ExactMesh& mesh) {
  std::vector<ExactPoint> points;
  points.reserve(mesh.number_of_vertices());
  for (auto v : mesh.vertices())
    if (!mesh.is_isolated(v)) points.push_back(mesh.point(v));
  std::sort(points.begin(), points.end(), ExactPointLess());
  return std::adjacent_find(points.begin(), points.end()) != points.end();
}

}  // namespace subfab::detail
