// SPDX-License-Identifier: GPL-3.0-or-later
#include "unfold/triangulate_facets.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <list>

#include "subfab/core/error.h"
#include "subfab/unfold/lattice_directions.h"

namespace subfab::unfold_detail {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
struct FaceInfo {
  int level = -1;
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fbb = CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbb>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

// Nesting level of every face: 0 outside, 1 in the facet, 2 in a hole, ...
void mark_levels(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info().level = -1;
  std::list<Cdt::Edge> border;
  auto flood = [&](Cdt::Face_handle start, int level) {
    if (start->info().level != -1) return;
    std::list<Cdt::Face_handle> queue{start};
    while (!queue.empty()) {
      Cdt::Face_handle f = queue.front();
      queue.pop_front();
      if (f->info().level != -1) continue;
      f->info().level = level;
      for (int i = 0; i < 3; ++i) {
        Cdt::Face_handle n = f->neighbor(i);
        if (n->info().level != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i)))
          border.push_back(Cdt::Edge(f, i));
        else
          queue.push_back(n);
      }
    }
  };
  flood(cdt.infinite_face(), 0);
  while (!border.empty()) {
    Cdt::Edge e = border.front();
    border.pop_front();
    Cdt::Face_handle n = e.first->neighbor(e.second);
    if (n->info().level == -1) flood(n, e.first->info().level + 1);
  }
}

}  // namespace

Mesh triangulate_facets(const PolyMesh& poly, std::vector<int>* face_facet) {
  Mesh out;
  out.vertices = poly.vertices;
  if (face_facet) face_facet->clear();
  for (std::size_t f = 0; f < poly.facets.size(); ++f) {
    const Facet& facet = poly.facets[f];
    const auto& outer = facet.loops[0];
    if (facet.loops.size() == 1 && outer.size() == 3) {
      out.faces.push_back({outer[0], outer[1], outer[2]});
      if (face_facet) face_facet->push_back(static_cast<int>(f));
      continue;
    }
    Vec3 n = Vec3::Zero();
    for (std::size_t i = 0; i < outer.size(); ++i)
      n += poly.vertices[outer[i]].cross(poly.vertices[outer[(i + 1) % outer.size()]]);
    n.normalize();
    const Vec3 e1 = (n.cross(Vec3::UnitX()).norm() > 0.5 ? n.cross(Vec3::UnitX()) : n.cross(Vec3::UnitY())).normalized();
    const Vec3 e2 = n.cross(e1);
    Cdt cdt;
    for (const auto& loop : facet.loops) {
      std::vector<Cdt::Vertex_handle> handles;
      for (int v : loop) {
        const Vec3& p = poly.vertices[v];
        auto h = cdt.insert(K::Point_2(p.dot(e1), p.dot(e2)));
        h->info() = v;
        handles.push_back(h);
      }
      for (std::size_t i = 0; i < handles.size(); ++i)
        cdt.insert_constraint(handles[i], handles[(i + 1) % handles.size()]);
    }
    mark_levels(cdt);
    for (auto fit = cdt.finite_faces_begin(); fit != cdt.finite_faces_end(); ++fit) {
      if (fit->info().level % 2 != 1) continue;
      out.faces.push_back({fit->vertex(0)->info(), fit->vertex(1)->info(), fit->vertex(2)->info()});
      if (face_facet) face_facet->push_back(static_cast<int>(f));
    }
  }
  return out;
}

}  // namespace subfab::unfold_detail
