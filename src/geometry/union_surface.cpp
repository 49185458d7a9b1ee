// SPDX-License-Identifier: GPL-3.0-or-later
// The boundary of a union of closed solids that may touch non-manifoldly,
// as faces of the corefined operands (see union_surface.h).
#include "geometry/union_surface.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/Side_of_triangle_mesh.h>

#include <algorithm>
#include <map>
#include <optional>
#include <memory>

namespace subfab::detail {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<ExactMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<ExactKernel, Primitive>>;
using SideOf = CGAL::Side_of_triangle_mesh<ExactMesh, ExactKernel, CGAL::Default, Tree>;

struct Corners {
  ExactPoint a, b, c;
};

Corners corners(const ExactMesh& m, FaceIndex f) {
  const HalfedgeIndex h = m.halfedge(f);
  return {m.point(m.source(h)), m.point(m.target(h)), m.point(m.target(m.next(h)))};
}

ExactKernel::Vector_3 normal(const Corners& t) { return CGAL::cross_product(t.b - t.a, t.c - t.a); }

//! How a face of one operand lies against another operand.
enum class Side { Outside, Inside, OnSameWay, OnOppositeWay, Unknown };

//! Which faces of the corefined operands bound the result.
enum class Operation { Union, Difference };

//! Step 2 of union_surface(), shared with difference_surface(): classifies
//! one face per patch of the corefined `operands` against every other
//! operand as `given` and keeps the faces `operation`'s rule keeps.
bool classify_corefined(const std::vector<ExactMesh>& operands, const std::vector<ExactMesh>& given,
                        Operation operation, std::vector<std::pair<std::size_t, FaceIndex>>& kept) {
  kept.clear();
  const std::size_t m = operands.size();
  // CGAL 5.5's corefinement can leave a broken mesh (a face around a null
  // vertex: seen in a union, measure_fill_deviation.cpp): refused, not read.
  for (const ExactMesh& o : operands)
    if (!CGAL::is_valid_polygon_mesh(o)) return false;
  std::vector<CGAL::Bbox_3> box(m);
  for (std::size_t a = 0; a < m; ++a) box[a] = PMP::bbox(given[a]);
  // 2. classify one interior point of every face against the other operands
  //    as given (see union_surface(): the side of a point does not depend on
  //    how an operand is refined, and the given coordinates are smaller)
  std::vector<std::unique_ptr<Tree>> trees(m);
  std::vector<std::unique_ptr<SideOf>> sides(m);
  for (std::size_t b = 0; b < m; ++b) {
    trees[b] = std::make_unique<Tree>(faces(given[b]).first, faces(given[b]).second, given[b]);
    trees[b]->build();
    sides[b] = std::make_unique<SideOf>(*trees[b]);
  }
  // The operands that have a vertex at each vertex position (sorted).
  std::map<ExactPoint, std::vector<std::size_t>, ExactPointLess> owners;
  for (std::size_t b = 0; b < m; ++b)
    for (VertexIndex v : operands[b].vertices()) {
      std::vector<std::size_t>& o = owners[operands[b].point(v)];
      if (o.empty() || o.back() != b) o.push_back(b);
    }
  auto is_vertex_of = [&](const ExactPoint& p, std::size_t b) {
    const std::vector<std::size_t>& o = owners.at(p);
    return std::binary_search(o.begin(), o.end(), b);
  };
  // Face f of O_a against O_b.
  auto side_of = [&](const Corners& t, std::optional<ExactPoint>& centroid, std::size_t b) -> Side {
    // A corner of f that is not a vertex of O_b lies off ∂O_b (the
    // corefinement made every point of O_a on ∂O_b a vertex of both), and
    // f's interior is on its side (no point of the open face or of the
    // open edges from that corner is on ∂O_b, for the same reason): that
    // corner is classified (input or once-constructed coordinates: far
    // cheaper exactly than a centroid of constructed points, issue 17).
    const ExactPoint* corner = nullptr;
    for (const ExactPoint* q : {&t.a, &t.b, &t.c})
      if (!is_vertex_of(*q, b)) {
        corner = q;
        break;
      }
    if (corner) {
      if (!CGAL::do_overlap(corner->bbox(), box[b])) return Side::Outside;
      const CGAL::Bounded_side side = (*sides[b])(*corner);
      if (side == CGAL::ON_BOUNDED_SIDE) return Side::Inside;
      if (side == CGAL::ON_BOUNDARY) return Side::Unknown;  // cannot happen after a correct corefinement
      return Side::Outside;
    }
    if (!centroid) centroid = CGAL::centroid(t.a, t.b, t.c);
    const ExactPoint& p = *centroid;
    if (!CGAL::do_overlap(p.bbox(), box[b])) return Side::Outside;
    // on ∂O_b? Then f lies in a coplanar face g of O_b (after the
    // corefinement nothing else can hold its interior point). Asked first:
    // a ray from a point on ∂O_b makes the side test's predicates exact.
    std::vector<Tree::Primitive_id> under;
    trees[b]->all_intersected_primitives(p, std::back_inserter(under));
    for (FaceIndex g : under) {
      const Corners u = corners(given[b], g);  // the given face holding f's refined copy
      if (CGAL::orientation(u.a, u.b, u.c, t.a) != CGAL::COPLANAR ||
          CGAL::orientation(u.a, u.b, u.c, t.b) != CGAL::COPLANAR ||
          CGAL::orientation(u.a, u.b, u.c, t.c) != CGAL::COPLANAR)
        continue;
      return CGAL::sign(normal(t) * normal(u)) > 0 ? Side::OnSameWay : Side::OnOppositeWay;
    }
    if (!under.empty()) return Side::Unknown;
    const CGAL::Bounded_side side = (*sides[b])(p);
    if (side == CGAL::ON_BOUNDED_SIDE) return Side::Inside;
    if (side == CGAL::ON_BOUNDARY) return Side::Unknown;
    return Side::Outside;
  };
  // 1 keep, 0 drop, -1 no coplanar face under a face on another operand's boundary
  auto classify = [&](std::size_t a, FaceIndex f) -> char {
    const Corners t = corners(operands[a], f);
    std::optional<ExactPoint> centroid;
    if (operation == Operation::Difference) {
      // ∂(O_0 \ O_1): O_0's faces outside O_1, or on ∂O_1 facing the other
      // way (O_0 lies outside O_1 there); O_1's faces inside O_0 (on ∂O_0
      // they are O_0's faces already, or no boundary).
      const Side s = side_of(t, centroid, 1 - a);
      if (s == Side::Unknown) return -1;
      if (a == 0) return s == Side::Outside || s == Side::OnOppositeWay ? 1 : 0;
      return s == Side::Inside ? 1 : 0;
    }
    for (std::size_t b = 0; b < m; ++b) {
      if (b == a) continue;
      const Side s = side_of(t, centroid, b);
      if (s == Side::Unknown) return -1;
      if (s == Side::Inside || s == Side::OnOppositeWay) return 0;
      if (s == Side::OnSameWay && b < a) return 0;  // one copy of a shared face
    }
    return 1;
  };
  // Patches: faces joined across edges that cannot lie on another operand's
  // surface. After corefinement such a surface meets an edge only along the
  // whole edge (then both ends are vertices of that operand: corefinement
  // puts every intersection point in both meshes) or at its ends, so two
  // faces across any other edge are on the same side of every operand, and
  // one face per patch is classified.
  // a vertex position -> its first operand, or m if several
  auto owner_of = [&](const ExactPoint& p) {
    const std::vector<std::size_t>& o = owners.at(p);
    return o.size() == 1 ? o[0] : m;
  };
  for (std::size_t a = 0; a < m; ++a) {
    const ExactMesh& o = operands[a];
    std::vector<char> shared(o.num_vertices(), 0);  // the vertex's position is a vertex of another operand
    for (VertexIndex v : o.vertices()) shared[v.idx()] = owner_of(o.point(v)) != a ? 1 : 0;
    std::vector<int> patch(o.num_faces(), -1);
    std::vector<char> patch_kept;
    for (FaceIndex start : o.faces()) {
      if (patch[start.idx()] >= 0) continue;
      const int id = static_cast<int>(patch_kept.size());
      patch_kept.push_back(classify(a, start));
      std::vector<FaceIndex> stack{start};
      patch[start.idx()] = id;
      while (!stack.empty()) {
        const FaceIndex f = stack.back();
        stack.pop_back();
        for (HalfedgeIndex h : CGAL::halfedges_around_face(o.halfedge(f), o)) {
          if (shared[o.source(h).idx()] && shared[o.target(h).idx()]) continue;
          const FaceIndex g = o.face(o.opposite(h));
          if (g == ExactMesh::null_face() || patch[g.idx()] >= 0) continue;
          patch[g.idx()] = id;
          stack.push_back(g);
        }
      }
    }
    for (FaceIndex f : o.faces()) {
      const char k = patch_kept[static_cast<std::size_t>(patch[f.idx()])];
      if (k < 0) return false;
      if (k) kept.emplace_back(a, f);
    }
  }
  return true;
}

}  // namespace

bool union_surface(std::vector<ExactMesh>& operands, std::vector<std::pair<std::size_t, FaceIndex>>& kept) {
  kept.clear();
  const std::size_t m = operands.size();
  for (const ExactMesh& o : operands)
    if (has_coincident_vertices(o)) return false;
  std::vector<CGAL::Bbox_3> box(m);
  for (std::size_t a = 0; a < m; ++a) box[a] = PMP::bbox(operands[a]);
  // Self-intersections are checked once, on the operands as given (CGAL's
  // corefinement requires none; refining a mesh never creates one), not by
  // each corefinement: those checks, repeated on meshes already refined by
  // earlier pairs (constructed points of 300-1000 bits), were a third of
  // the overlay's time (issue 17, bench/RESULTS.md "fillfast").
  for (const ExactMesh& o : operands)
    if (PMP::does_self_intersect(o)) throw PMP::Corefinement::Self_intersection_exception();
  // The operands as given: classifying a point against O_b does not depend
  // on how O_b is refined, and the given faces have far smaller exact
  // coordinates than the refined ones (the side tests' exact fallbacks).
  const std::vector<ExactMesh> given = operands;
  // 1. corefine every pair whose boxes meet (closed boxes: touching counts)
  for (std::size_t a = 0; a < m; ++a)
    for (std::size_t b = a + 1; b < m; ++b)
      if (CGAL::do_overlap(box[a], box[b])) PMP::corefine(operands[a], operands[b]);
  return classify_corefined(operands, given, Operation::Union, kept);
}

bool difference_surface(const std::vector<ExactMesh>& corefined, const std::vector<ExactMesh>& given,
                        std::vector<std::pair<std::size_t, FaceIndex>>& kept) {
  if (corefined.size() != 2 || given.size() != 2)
    throw InvalidArgumentError("difference_surface: two operands expected");
  for (const ExactMesh& o : given)
    if (has_coincident_vertices(o)) return false;
  return classify_corefined(corefined, given, Operation::Difference, kept);
}

}  // namespace subfab::detail
