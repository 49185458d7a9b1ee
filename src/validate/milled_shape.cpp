// SPDX-License-Identifier: GPL-3.0-or-later
// milled_shape(): the upper envelope of a block's upward faces (CGAL
// Envelope_3 on the exact kernel), lifted, walled and closed by its base.
// See milled_shape.h for the outline.
#include "subfab/validate/milled_shape.h"

#include <CGAL/Arr_default_overlay_traits.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_landmarks_point_location.h>
#include <CGAL/Arr_overlay_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Env_surface_data_traits_3.h>
#include <CGAL/Env_triangle_traits_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/envelope_3.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "geometry/exact_mesh.h"
#include "geometry/rotate_accurately.h"
#include "subfab/core/error.h"
#include "subfab/validate/validate_decomposition.h"

namespace subfab {
namespace {

using K = detail::ExactKernel;
using FT = K::FT;
using Point2 = K::Point_2;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using EnvTraits = CGAL::Env_triangle_traits_3<K>;
using Traits = CGAL::Env_surface_data_traits_3<EnvTraits, int>;  // each triangle carries its index
using Surface = Traits::Xy_monotone_surface_3;
using Diagram = CGAL::Envelope_diagram_2<Traits>;
//! The top surface as a planar map: each face carries the index of the
//! triangle on top of it (-1: nothing, the base).
using Map = CGAL::Arrangement_2<Traits, CGAL::Arr_face_extended_dcel<Traits, int>>;
using FaceH = Map::Face_const_handle;
using HalfedgeH = Map::Halfedge_const_handle;

using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Fb = CGAL::Triangulation_face_base_with_info_2<int, K, CGAL::Constrained_triangulation_face_base_2<K>>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;

//! x rounded to the nearest double; without the exact evaluation when x's
//! interval is a single double (an input coordinate: the exact value is it).
double round_exact(const FT& x) {
  const CGAL::Interval_nt<false>& i = x.approx();
  if (i.inf() == i.sup()) return i.inf();
  return CGAL::to_double(CGAL::exact(x));
}

//! Marks the faces of `cdt` with their nesting level (number of constraints
//! crossed from the infinite face): odd levels are inside the polygon.
void mark_nesting(Cdt& cdt) {
  for (auto f : cdt.all_face_handles()) f->info() = -1;
  std::deque<std::pair<Cdt::Face_handle, int>> border{{cdt.infinite_face(), 0}};
  while (!border.empty()) {
    const auto [start, level] = border.front();
    border.pop_front();
    if (start->info() != -1) continue;
    std::deque<Cdt::Face_handle> queue{start};
    start->info() = level;
    while (!queue.empty()) {
      const Cdt::Face_handle f = queue.front();
      queue.pop_front();
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle n = f->neighbor(i);
        if (n->info() != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i))) {
          border.emplace_back(n, level + 1);
        } else {
          n->info() = level;
          queue.push_back(n);
        }
      }
    }
  }
}

//! Builds the milled solid from the envelope diagram, in the milling frame.
class MilledBuilder {
 public:
  MilledBuilder(const Map& diagram, const std::vector<std::array<K::Point_3, 3>>& triangles, double base)
      : diagram_(diagram), triangles_(triangles), base_(base) {}

  void build() {
    index_diagram();
    for (auto e = diagram_.edges_begin(); e != diagram_.edges_end(); ++e) split_edge(e);
    for (std::size_t f = 0; f < faces_.size(); ++f)
      if (planes_[f]) triangulate_face(f);
    for (auto e = diagram_.edges_begin(); e != diagram_.edges_end(); ++e) add_walls(e);
  }

  Mesh mesh;                               // milling frame, rounded
  std::vector<MilledFaceKind> kinds;       // per face of mesh
  std::size_t num_envelope_faces = 0;

 private:
  struct Plane {
    FT a, b, c, d;
  };

  //! Numbers the diagram's vertices (point ids) and faces; keeps each face's plane.
  void index_diagram() {
    for (auto v = diagram_.vertices_begin(); v != diagram_.vertices_end(); ++v) {
      vertex_id_.emplace(&*v, static_cast<int>(points_.size()));
      points_.push_back(v->point());
    }
    lifted_.resize(points_.size());
    for (auto f = diagram_.faces_begin(); f != diagram_.faces_end(); ++f) {
      face_id_.emplace(&*f, faces_.size());
      faces_.push_back(f);
      if (f->data() < 0) {
        planes_.emplace_back();
        continue;
      }
      const auto& t = triangles_[static_cast<std::size_t>(f->data())];
      const K::Plane_3 p(t[0], t[1], t[2]);
      planes_.push_back(Plane{p.a(), p.b(), p.c(), p.d()});
      ++num_envelope_faces;
    }
  }

  int point_id(Map::Vertex_const_handle v) const { return vertex_id_.at(&*v); }
  std::size_t face_id(FaceH f) const { return face_id_.at(&*f); }

  //! Height of face f's top at point `pid` (the base for an empty face).
  FT height(std::size_t f, int pid) {
    if (!planes_[f]) return FT(base_);
    const std::uint64_t key = (static_cast<std::uint64_t>(f) << 32) | static_cast<std::uint32_t>(pid);
    auto it = height_cache_.find(key);
    if (it != height_cache_.end()) return it->second;
    const Point2& q = points_[static_cast<std::size_t>(pid)];
    // At a corner of the face's triangle the height is the corner's own z
    // (exact, and a double: no exact evaluation later when it is compared
    // or rounded). Most points of the diagram are such corners.
    for (const K::Point_3& c : triangles_[static_cast<std::size_t>(faces_[f]->data())])
      if (q.x() == c.x() && q.y() == c.y()) {
        height_cache_.emplace(key, c.z());
        return c.z();
      }
    const Plane& p = *planes_[f];
    FT h = -(p.a * q.x() + p.b * q.y() + p.d) / p.c;
    height_cache_.emplace(key, h);
    return h;
  }

  //! The output vertex over point `pid` at height h (shared, exact).
  int vertex(int pid, const FT& h) {
    auto& list = lifted_[static_cast<std::size_t>(pid)];
    for (const auto& [hh, id] : list)
      if (hh == h) return id;
    const Point2& q = points_[static_cast<std::size_t>(pid)];
    const int id = static_cast<int>(mesh.vertices.size());
    mesh.vertices.emplace_back(round_exact(q.x()), round_exact(q.y()), round_exact(h));
    list.emplace_back(h, id);
    return id;
  }

  void triangle(int a, int b, int c, MilledFaceKind kind) {
    mesh.faces.push_back({a, b, c});
    kinds.push_back(kind);
  }

  //! Where the two sides' heights cross strictly inside an edge, the edge is
  //! split there (both faces' boundaries and the wall get the point).
  void split_edge(Map::Edge_const_iterator e) {
    const HalfedgeH h = e;
    const std::size_t f1 = face_id(h->face()), f2 = face_id(h->twin()->face());
    if (f1 == f2) return;
    const int s = point_id(h->source()), t = point_id(h->target());
    const FT ds = height(f1, s) - height(f2, s), dt = height(f1, t) - height(f2, t);
    if (CGAL::sign(ds) * CGAL::sign(dt) >= 0) return;
    const FT lambda = ds / (ds - dt);
    const Point2& ps = points_[static_cast<std::size_t>(s)];
    const Point2& pt = points_[static_cast<std::size_t>(t)];
    const int m = static_cast<int>(points_.size());
    points_.emplace_back(ps.x() + lambda * (pt.x() - ps.x()), ps.y() + lambda * (pt.y() - ps.y()));
    lifted_.emplace_back();
    split_.emplace(&*h, m);
    split_.emplace(&*h->twin(), m);
  }

  int split_point(HalfedgeH h) const {
    auto it = split_.find(&*h);
    return it == split_.end() ? -1 : it->second;
  }

  //! Top (lifted onto its triangle) and base of one envelope face.
  void triangulate_face(std::size_t f) {
    const FaceH face = faces_[f];
    Cdt cdt;
    std::unordered_map<int, Cdt::Vertex_handle> handle;
    auto insert = [&](int pid) {
      auto it = handle.find(pid);
      if (it != handle.end()) return it->second;
      const Cdt::Vertex_handle v = cdt.insert(points_[static_cast<std::size_t>(pid)]);
      v->info() = pid;
      handle.emplace(pid, v);
      return v;
    };
    auto add_ccb = [&](Map::Ccb_halfedge_const_circulator first) {
      auto c = first;
      do {
        const HalfedgeH h = c;
        if (h->twin()->face() != face) {  // antennas bound nothing
          const int s = point_id(h->source()), t = point_id(h->target()), m = split_point(h);
          if (m < 0) {
            cdt.insert_constraint(insert(s), insert(t));
          } else {
            cdt.insert_constraint(insert(s), insert(m));
            cdt.insert_constraint(insert(m), insert(t));
          }
        }
      } while (++c != first);
    };
    if (!face->is_unbounded()) add_ccb(face->outer_ccb());
    for (auto hole = face->inner_ccbs_begin(); hole != face->inner_ccbs_end(); ++hole) add_ccb(*hole);
    mark_nesting(cdt);
    const FT base(base_);
    for (auto t : cdt.finite_face_handles()) {
      if (t->info() % 2 != 1) continue;
      const int p0 = t->vertex(0)->info(), p1 = t->vertex(1)->info(), p2 = t->vertex(2)->info();
      triangle(vertex(p0, height(f, p0)), vertex(p1, height(f, p1)), vertex(p2, height(f, p2)), MilledFaceKind::Top);
      triangle(vertex(p0, base), vertex(p2, base), vertex(p1, base), MilledFaceKind::Base);
    }
  }

  //! The heights of the faces around point `pid` (a diagram vertex) or the
  //! one height of a split point, ascending and distinct.
  std::vector<FT> heights_at(int pid, Map::Vertex_const_handle v, std::size_t f) {
    std::vector<FT> hs;
    if (v == Map::Vertex_const_handle()) {
      hs.push_back(height(f, pid));
      return hs;
    }
    auto c = v->incident_halfedges(), first = c;
    do hs.push_back(height(face_id(c->face()), pid));
    while (++c != first);
    std::sort(hs.begin(), hs.end());
    hs.erase(std::unique(hs.begin(), hs.end()), hs.end());
    return hs;
  }

  //! The heights of `all` in [lo, hi], ascending.
  static std::vector<FT> between(const std::vector<FT>& all, const FT& lo, const FT& hi) {
    std::vector<FT> out;
    for (const FT& h : all)
      if (h >= lo && h <= hi) out.push_back(h);
    return out;
  }

  //! Vertical wall over the segment s -> t, between the heights L (at s) and
  //! R (at t), ascending; the solid is on the left of s -> t seen from +z, so
  //! the wall faces right. Zipper triangulation (never a degenerate triangle).
  void wall(int s, int t, const std::vector<FT>& L, const std::vector<FT>& R) {
    std::size_t i = 0, j = 0;
    const std::size_t m = L.size() - 1, n = R.size() - 1;
    while (i < m || j < n) {
      if (i == m || (j < n && R[j + 1] <= L[i + 1])) {
        triangle(vertex(s, L[i]), vertex(t, R[j]), vertex(t, R[j + 1]), MilledFaceKind::Wall);
        ++j;
      } else {
        triangle(vertex(s, L[i]), vertex(t, R[j]), vertex(s, L[i + 1]), MilledFaceKind::Wall);
        ++i;
      }
    }
  }

  //! The walls along one diagram edge (two when it is split).
  void add_walls(Map::Edge_const_iterator e) {
    const HalfedgeH h = e;
    const std::size_t f1 = face_id(h->face()), f2 = face_id(h->twin()->face());
    if (f1 == f2) return;
    const int src = point_id(h->source()), dst = point_id(h->target()), m = split_point(h);
    using VH = Map::Vertex_const_handle;
    std::vector<std::pair<int, VH>> chain{{src, h->source()}};
    if (m >= 0) chain.emplace_back(m, VH());
    chain.emplace_back(dst, h->target());
    for (std::size_t k = 0; k + 1 < chain.size(); ++k) {
      auto [s, vs] = chain[k];
      auto [t, vt] = chain[k + 1];
      const FT s1 = height(f1, s), s2 = height(f2, s), t1 = height(f1, t), t2 = height(f2, t);
      if (s1 == s2 && t1 == t2) continue;
      const bool left_high = s1 >= s2 && t1 >= t2;  // face 1 (left of h) is the higher side
      const std::vector<FT> hs = heights_at(s, vs, f1), ht = heights_at(t, vt, f1);
      if (left_high)
        wall(s, t, between(hs, s2, s1), between(ht, t2, t1));
      else
        wall(t, s, between(ht, t1, t2), between(hs, s1, s2));
    }
  }

  const Map& diagram_;
  const std::vector<std::array<K::Point_3, 3>>& triangles_;  // the upward triangles, milling frame
  double base_;
  std::vector<Point2> points_;                          // point id -> 2D point
  std::vector<std::vector<std::pair<FT, int>>> lifted_;  // point id -> (height, output vertex)
  std::vector<FaceH> faces_;
  std::vector<std::optional<Plane>> planes_;            // face id -> plane of its top (none: empty)
  std::unordered_map<const void*, int> vertex_id_;
  std::unordered_map<const void*, std::size_t> face_id_;
  std::unordered_map<const void*, int> split_;          // halfedge -> split point id
  std::unordered_map<std::uint64_t, FT> height_cache_;
};

//! Do the interiors of two counter-clockwise triangles overlap? (Exact:
//! they do not iff an edge line of one leaves the other on its closed right.)
bool interiors_overlap(const std::array<Epick::Point_2, 3>& a, const std::array<Epick::Point_2, 3>& b) {
  for (const auto* t : {&a, &b}) {
    const auto& o = t == &a ? b : a;
    for (std::size_t k = 0; k < 3; ++k) {
      const Epick::Point_2 &p = (*t)[k], &q = (*t)[(k + 1) % 3];
      if (CGAL::orientation(p, q, o[0]) != CGAL::LEFT_TURN && CGAL::orientation(p, q, o[1]) != CGAL::LEFT_TURN &&
          CGAL::orientation(p, q, o[2]) != CGAL::LEFT_TURN)
        return false;
    }
  }
  return true;
}

//! Which triangles' projections overlap another's: the only ones whose tops
//! can hide each other (elsewhere each triangle is the top surface itself).
std::vector<char> stacked_triangles(const std::vector<std::array<Epick::Point_2, 3>>& shadow) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;
  std::vector<Box> boxes;
  boxes.reserve(shadow.size());
  for (std::size_t i = 0; i < shadow.size(); ++i)
    boxes.emplace_back(shadow[i][0].bbox() + shadow[i][1].bbox() + shadow[i][2].bbox(), i);
  std::vector<char> stacked(shadow.size(), 0);
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    if (interiors_overlap(shadow[x.info()], shadow[y.info()])) stacked[x.info()] = stacked[y.info()] = 1;
  });
  return stacked;
}

//! Does an end of one of `edges` (distinct segments, in doubles) lie inside
//! another, or on it but off its ends? Exact. The edges of triangles whose
//! projections overlap nothing cross nowhere (a crossing would overlap two
//! interiors), so without such a touch they meet only at common ends: what
//! insert_non_intersecting_curves() needs.
bool touching_edges(const std::vector<std::array<Epick::Point_2, 2>>& edges) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;
  std::vector<Box> boxes;
  boxes.reserve(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) boxes.emplace_back(edges[i][0].bbox() + edges[i][1].bbox(), i);
  const auto inside = [](const std::array<Epick::Point_2, 2>& e, const Epick::Point_2& p) {
    return p != e[0] && p != e[1] && CGAL::collinear(e[0], e[1], p) &&
           CGAL::collinear_are_strictly_ordered_along_line(e[0], p, e[1]);
  };
  bool touch = false;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    if (touch) return;
    const auto &a = edges[x.info()], &b = edges[y.info()];
    touch = inside(a, b[0]) || inside(a, b[1]) || inside(b, a[0]) || inside(b, a[1]);
  });
  return touch;
}

//! Sets each face of `result` to the triangle on top of it: the diagram's
//! (an upper envelope) or the map's (projections that overlap nothing).
class TopOverlay : public CGAL::_Arr_default_overlay_traits_base<Diagram, Map, Map> {
 public:
  void create_face(Diagram::Face_const_handle a, Map::Face_const_handle b, Map::Face_handle r) const override {
    const int la = a->number_of_surfaces() > 0 ? a->surface().data() : -1;
    if (la >= 0 && b->data() >= 0) both = true;
    r->set_data(la >= 0 ? la : b->data());
  }
  mutable bool both = false;  // a face with a triangle from each: their projections overlap
};

//! The top surface of the triangles `up` (milling frame, facing +z) as a
//! planar map. Only the triangles whose projections overlap another's go
//! through CGAL's upper envelope (exact, and the costly part); the others
//! are the top surface themselves: their projected edges are inserted into
//! a planar map, each face labelled by point location of its triangle's
//! centroid, and the two are overlaid.
Map top_surface(const std::vector<std::array<K::Point_3, 3>>& up,
                const std::vector<std::array<Epick::Point_2, 3>>& shadow) {
  const std::vector<char> stacked = stacked_triangles(shadow);
  std::vector<Surface> surfaces;
  std::vector<Traits::X_monotone_curve_2> edges;
  std::vector<std::array<Epick::Point_2, 2>> plain;  // the same edges, in doubles
  std::vector<std::pair<Point2, int>> centroids;
  std::set<std::pair<Point2, Point2>, bool (*)(const std::pair<Point2, Point2>&, const std::pair<Point2, Point2>&)>
      seen([](const std::pair<Point2, Point2>& x, const std::pair<Point2, Point2>& y) {
        const CGAL::Comparison_result c = CGAL::compare_xy(x.first, y.first);
        return c == CGAL::SMALLER || (c == CGAL::EQUAL && CGAL::compare_xy(x.second, y.second) == CGAL::SMALLER);
      });
  for (std::size_t i = 0; i < up.size(); ++i) {
    const auto& t = up[i];
    if (stacked[i]) {
      surfaces.emplace_back(EnvTraits::Xy_monotone_surface_3(t[0], t[1], t[2]), static_cast<int>(i));
      continue;
    }
    std::array<Point2, 3> p{Point2(t[0].x(), t[0].y()), Point2(t[1].x(), t[1].y()), Point2(t[2].x(), t[2].y())};
    for (std::size_t k = 0; k < 3; ++k) {
      Point2 a = p[k], b = p[(k + 1) % 3];
      if (CGAL::compare_xy(b, a) == CGAL::SMALLER) std::swap(a, b);
      if (seen.emplace(a, b).second) {  // each edge once
        edges.emplace_back(a, b);
        plain.push_back({shadow[i][k], shadow[i][(k + 1) % 3]});
      }
    }
    centroids.emplace_back(CGAL::centroid(p[0], p[1], p[2]), static_cast<int>(i));
  }
  Diagram diagram;
  if (!surfaces.empty()) CGAL::upper_envelope_xy_monotone_3(surfaces.begin(), surfaces.end(), diagram);
  Map flat;
  if (touching_edges(plain))
    CGAL::insert(flat, edges.begin(), edges.end());
  else  // the usual case: no sweep for intersections needed
    CGAL::insert_non_intersecting_curves(flat, edges.begin(), edges.end());
  for (auto f = flat.faces_begin(); f != flat.faces_end(); ++f) f->set_data(-1);
  {
    CGAL::Arr_landmarks_point_location<Map> locator(flat);
    for (const auto& [c, i] : centroids) {
      const auto where = locator.locate(c);  // strictly inside its triangle, which no edge crosses
      const Map::Face_const_handle* f = boost::get<Map::Face_const_handle>(&where);
      if (!f) throw AlgorithmError("milled_shape: a triangle's centroid is not inside a face of its map");
      flat.non_const_handle(*f)->set_data(i);
    }
  }
  Map result;
  TopOverlay labels;
  CGAL::overlay(diagram, flat, result, labels);
  if (labels.both) throw AlgorithmError("milled_shape: triangles marked apart overlap (internal error)");
  return result;
}

bool is_rotation_to_z(const Eigen::Matrix3d& q, const Vec3& d) {
  return (q.transpose() * q - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-9 && q.determinant() > 0 &&
         (q * d - Vec3::UnitZ()).norm() <= 1e-9;
}

}  // namespace

Eigen::Matrix3d milling_frame(const Vec3& d) {
  Eigen::Matrix3d q;
  for (int k = 0; k < 3; ++k)
    for (int s : {1, -1}) {
      if (d != s * Vec3::Unit(k)) continue;
      // A signed permutation: rows (e_u, e_v, s e_k) with (u, v, k) cyclic,
      // the second row negated when s = -1 (keeps the determinant +1).
      const int u = (k + 1) % 3, v = (k + 2) % 3;
      q.setZero();
      q(0, u) = 1;
      q(1, v) = s;
      q(2, k) = s;
      return q;
    }
  const Vec3 z = d.normalized();
  int least = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(z[k]) < std::abs(z[least])) least = k;
  const Vec3 x = Vec3::Unit(least).cross(z).normalized();
  const Vec3 y = z.cross(x);
  q.row(0) = x.transpose();
  q.row(1) = y.transpose();
  q.row(2) = z.transpose();
  return q;
}

MilledShape milled_shape(const Mesh& block, const Vec3& direction, const MilledShapeOptions& options) {
  if (!(std::abs(direction.norm() - 1.0) <= 1e-9))
    throw InvalidArgumentError("milled_shape: the milling direction must be a unit vector");
  const Eigen::Matrix3d q = options.frame ? *options.frame : milling_frame(direction);
  if (!is_rotation_to_z(q, direction))
    throw InvalidArgumentError("milled_shape: the frame must be a rotation taking the milling direction to +z");
  MilledShape out;
  HeightFieldOptions ho;
  ho.normal_tolerance = options.normal_tolerance;
  ho.plane_tolerance = options.plane_tolerance;
  const HeightFieldReport hf = check_height_field(block, direction, ho);
  out.base = hf.base;
  if (hf.ok()) {
    out.mesh = block;
    out.is_block = true;
    return out;
  }
  // The block in the milling frame (d = +z), its base and its upward faces.
  std::vector<Vec3> r(block.num_vertices());
  double base = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < r.size(); ++i) {
    r[i] = detail::rotate_accurately(q, block.vertices[i]);
    base = std::min(base, r[i].z());
  }
  std::vector<std::array<K::Point_3, 3>> up;  // the faces facing +z (the only ones that can be on top)
  std::vector<std::array<Epick::Point_2, 3>> shadow;  // their projections, counter-clockwise
  for (const Triangle& t : block.faces) {
    const Vec3 &a = r[static_cast<std::size_t>(t[0])], &b = r[static_cast<std::size_t>(t[1])],
               &c = r[static_cast<std::size_t>(t[2])];
    const std::array<Epick::Point_2, 3> p{Epick::Point_2(a.x(), a.y()), Epick::Point_2(b.x(), b.y()),
                                          Epick::Point_2(c.x(), c.y())};
    if (CGAL::orientation(p[0], p[1], p[2]) != CGAL::LEFT_TURN) continue;  // faces -z or is vertical
    up.push_back({K::Point_3(a.x(), a.y(), a.z()), K::Point_3(b.x(), b.y(), b.z()), K::Point_3(c.x(), c.y(), c.z())});
    shadow.push_back(p);
  }
  const Map top = top_surface(up, shadow);
  MilledBuilder builder(top, up, base);
  builder.build();
  out.num_envelope_faces = builder.num_envelope_faces;
  out.mesh = std::move(builder.mesh);
  out.face_kinds = std::move(builder.kinds);
  const Eigen::Matrix3d back = q.transpose();
  for (Vec3& v : out.mesh.vertices) v = detail::rotate_accurately(back, v);
  return out;
}

}  // namespace subfab
