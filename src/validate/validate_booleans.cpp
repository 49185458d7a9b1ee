// SPDX-License-Identifier: GPL-3.0-or-later
// The CGAL parts of validate_decomposition.h: exact overlap and outside
// volumes (corefinement on an exact kernel) and the coverage distances
// (AABB tree on exact predicates). Where the corefinement cannot output a
// 2-manifold (blocks touching along an edge or at a point), the volumes are
// measured on Nef polyhedra, which represent non-manifold solids exactly.
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/clip.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "geometry/box_tests.h"
#include "geometry/deterministic_arena.h"
#include "geometry/exact_mesh.h"
#include "geometry/union_surface.h"
#include "validate/validate_booleans.h"
#include "subfab/checks/check_self_intersections.h"
#include "subfab/core/error.h"
#include "subfab/validate/validate_decomposition.h"

namespace subfab {

std::string detail::boolean_input_defect(const Mesh& m, bool whole_surface) {
  if (const std::size_t n = count_degenerate_faces(m))
    return "has " + std::to_string(n) + " degenerate (zero-area) faces; exact booleans cannot be run on it";
  if (whole_surface) {
    const CheckResult crossing = check_self_intersections(m);
    if (crossing.failed())
      return "intersects itself (" + std::to_string(crossing.num_offending) +
             " pairs of faces); exact booleans cannot be run on it";
  }
  return {};
}

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using detail::ExactMesh;

//! How a volume is evaluated: from the coordinates rounded to doubles (what
//! the checks print), or exactly (then independent of how the corefinement
//! triangulated the result, hence of the thread that ran it: what the
//! milled-shape measures report).
enum class Volume { Rounded, Exact };

//! The exact volume bounded by the triangles that `for_each` gives (it
//! calls its argument with the three corners of each, outward oriented),
//! rounded once: each triangle's exact determinant taken as a double-double,
//! summed with error-free transformations (the sum is within 1e-28 of the
//! exact volume, relative, before the final rounding).
template <class ForEachTriangle>
double exact_volume_of(ForEachTriangle for_each) {
  double hi = 0.0, lo = 0.0;
  auto add = [&](double x) {  // Knuth's two-sum into (hi, lo)
    const double s = hi + x, z = s - hi;
    lo += (hi - (s - z)) + (x - z);
    hi = s;
  };
  const detail::ExactPoint origin(0, 0, 0);
  for_each([&](const detail::ExactPoint& a, const detail::ExactPoint& b, const detail::ExactPoint& c) {
    const auto det = CGAL::exact(CGAL::determinant(a - origin, b - origin, c - origin));
    const double first = CGAL::to_double(det);
    add(first);
    add(CGAL::to_double(det - decltype(det)(first)));
  });
  return (hi + lo) / 6.0;
}

//! The exact volume of a closed mesh, rounded once (exact_volume_of()).
double exact_volume(const ExactMesh& m) {
  return exact_volume_of([&](auto&& triangle) {
    for (auto f : m.faces()) {
      const auto h = m.halfedge(f);
      triangle(m.point(m.source(h)), m.point(m.target(h)), m.point(m.target(m.next(h))));
    }
  });
}

double mesh_volume(const ExactMesh& m, Volume mode = Volume::Rounded) {
  return mode == Volume::Exact ? exact_volume(m) : signed_volume(detail::to_double(m));
}

//! CGAL's corefinement needs non-degenerate, self-intersection-free inputs:
//! refuse degenerate faces here, and ask it to throw (not crash) on
//! self-intersections near the intersection. A block (`whole_surface`) is
//! also checked whole for self-intersections (exact): CGAL 5.5's clip
//! crashed (segfault) on a block crossing itself away from where the
//! throwing test looks (validate of anchor.off at --tolerance 5e-4, block
//! 042). The input was checked when it was read.
void require_boolean_input(const Mesh& m, const char* what, bool whole_surface = false) {
  const std::string defect = detail::boolean_input_defect(m, whole_surface);
  if (!defect.empty()) throw AlgorithmError(std::string(what) + " " + defect);
}

const auto kThrowOnSelfIntersection = CGAL::parameters::throw_on_self_intersection(true);

//! Runs op, turning CGAL's self-intersection exception into an AlgorithmError.
template <typename Op>
bool guarded(Op op) {
  try {
    return op();
  } catch (const PMP::Corefinement::Self_intersection_exception&) {
    throw AlgorithmError("a block self-intersects near the boolean's cut; exact booleans cannot be run on it");
  }
}

}  // namespace

namespace {

using Nef = CGAL::Nef_polyhedron_3<detail::ExactKernel>;

//! The volume of a regularized Nef polyhedron, exactly (divergence theorem
//! over its boundary shells, each oriented with the volume on its inside),
//! then rounded.
double nef_volume(const Nef& nef) {
  if (nef.is_empty()) return 0.0;
  std::vector<detail::ExactPoint> points;
  std::vector<std::vector<std::size_t>> polygons;
  CGAL::convert_nef_polyhedron_to_polygon_soup(nef, points, polygons, /*triangulate_all_faces=*/true);
  detail::ExactKernel::FT six_volume = 0;
  const detail::ExactPoint origin(0, 0, 0);
  for (const auto& poly : polygons)
    for (std::size_t k = 1; k + 1 < poly.size(); ++k)
      six_volume += CGAL::determinant(points[poly[0]] - origin, points[poly[k]] - origin, points[poly[k + 1]] - origin);
  return CGAL::to_double(six_volume / 6);
}

//! vol(a ∩ b) or vol(a \ b) of two exact closed meshes on Nef polyhedra:
//! slower than the corefinement, but defined when the result is not a
//! 2-manifold (it is regularized: the lower-dimensional contact is dropped).
double nef_volume_of(const ExactMesh& a, const ExactMesh& b, NefBoolean op) {
  const Nef na(a), nb(b);
  const Nef result = op == NefBoolean::Intersection ? (na * nb) : (na - nb);
  return std::max(0.0, nef_volume(result.regularization()));
}

//! vol(x ∩ y) (`intersection`) or vol(x \ y) by CGAL's corefinement, run on
//! copies (it modifies its inputs); nullopt when the result would not be a
//! 2-manifold.
std::optional<double> corefined_volume(const ExactMesh& x, const ExactMesh& y, bool intersection,
                                       Volume mode = Volume::Rounded) {
  ExactMesh x2 = x, y2 = y, out;
  const bool ok = guarded([&] {
    return intersection
               ? PMP::corefine_and_compute_intersection(x2, y2, out, kThrowOnSelfIntersection, kThrowOnSelfIntersection)
               : PMP::corefine_and_compute_difference(x2, y2, out, kThrowOnSelfIntersection, kThrowOnSelfIntersection);
  });
  if (!ok) return std::nullopt;
  return mesh_volume(out, mode);
}

//! vol(a ∩ b) of two exact closed meshes. The corefinement first: a ∩ b;
//! where that is not a 2-manifold (the blocks touch along an edge),
//! vol(a) - vol(a \ b), else vol(b) - vol(b \ a); when none is, Nef
//! polyhedra.
double exact_overlap(const ExactMesh& a, const ExactMesh& b, Volume mode = Volume::Rounded) {
  if (const auto v = corefined_volume(a, b, true, mode)) return std::max(0.0, *v);
  if (const auto v = corefined_volume(a, b, false, mode)) return std::max(0.0, mesh_volume(a, mode) - *v);
  if (const auto v = corefined_volume(b, a, false, mode)) return std::max(0.0, mesh_volume(b, mode) - *v);
  return nef_volume_of(a, b, NefBoolean::Intersection);
}

//! m ∩ box, exactly; false when CGAL cannot clip it into a 2-manifold.
bool clip_to(ExactMesh& m, const BoundingBox& box) {
  const detail::ExactKernel::Iso_cuboid_3 cuboid(detail::ExactPoint(box.min.x(), box.min.y(), box.min.z()),
                                                 detail::ExactPoint(box.max.x(), box.max.y(), box.max.z()));
  return guarded([&] { return PMP::clip(m, cuboid, CGAL::parameters::clip_volume(true)); });
}

//! blocks_overlap() with its volumes evaluated by `mode`; `within`, when
//! given, a closed box known to hold a ∩ b up to a zero volume.
double overlap_volume(const Mesh& a, const Mesh& b, Volume mode, const BoundingBox* within = nullptr) {
  const BoundingBox ba = bounding_box(a), bb = bounding_box(b);
  if (!detail::interiors_meet(ba, bb)) return 0.0;
  require_boolean_input(a, "a block", true);
  require_boolean_input(b, "a block", true);
  // a ∩ b lies in the common box of their bounding boxes: clip both to it
  // first (exactly), so the boolean only sees the faces near the contact.
  // The box is widened by a margin so that no clip plane is a bounding plane
  // of the other block: each plane then cuts at most one of the two, and no
  // cut face is coplanar with a face of the other one. (CGAL 5.5's
  // corefinement crashed, segfault, on two valid clipped pieces whose cut
  // faces shared a plane: fertility blocks 82 and 114.)
  BoundingBox common;
  common.min = ba.min.cwiseMax(bb.min);
  common.max = ba.max.cwiseMin(bb.max);
  const double margin = 1e-3 * (common.max - common.min).norm();
  // Within a smaller box `within` (milled shapes: the boxes of their fills),
  // its planes may cut both blocks: a is clipped to it widened by the
  // margin, b by twice the margin, so a's cut faces lie inside b's clipped
  // piece and b's outside a's (no two cut faces share a plane). Where a
  // side of `within` lies within twice the margin of the common box's, both
  // take the common box's side widened by the margin (a plane
  // beyond one block's bounding plane: it cuts the other block only).
  BoundingBox box_a = common, box_b = common;
  for (int k = 0; k < 3; ++k) {
    box_a.min[k] = box_b.min[k] = common.min[k] - margin;
    box_a.max[k] = box_b.max[k] = common.max[k] + margin;
    if (!within) continue;
    if (within->max[k] <= common.min[k] || within->min[k] >= common.max[k]) return 0.0;  // no volume in common
    if (within->min[k] - 2 * margin > common.min[k]) {
      box_a.min[k] = within->min[k] - margin;
      box_b.min[k] = within->min[k] - 2 * margin;
    }
    if (within->max[k] + 2 * margin < common.max[k]) {
      box_a.max[k] = within->max[k] + margin;
      box_b.max[k] = within->max[k] + 2 * margin;
    }
  }
  {
    ExactMesh ea = detail::to_exact(a), eb = detail::to_exact(b);
    bool clipped = false;
    try {
      clipped = clip_to(ea, box_a) && clip_to(eb, box_b);
    } catch (const AlgorithmError&) {
      clipped = false;  // fall back to the whole blocks
    }
    if (clipped) {
      if (ea.number_of_faces() == 0 || eb.number_of_faces() == 0) return 0.0;
      try {
        return exact_overlap(ea, eb, mode);
      } catch (const AlgorithmError&) {
        // CGAL found the clipped pieces self-intersecting (a clip plane through
        // a block face can leave slivers it refuses): use the whole blocks.
      }
    }
  }
  return exact_overlap(detail::to_exact(a), detail::to_exact(b), mode);
}

//! volume_outside() with its volumes evaluated by `mode`.
double outside_volume(const Mesh& block, const Mesh& solid, Volume mode) {
  if (!detail::interiors_meet(bounding_box(block), bounding_box(solid))) return signed_volume(block);
  require_boolean_input(block, "the block", true);
  require_boolean_input(solid, "the input");
  const ExactMesh eb = detail::to_exact(block), es = detail::to_exact(solid);
  if (const auto v = corefined_volume(eb, es, false, mode)) return std::max(0.0, *v);
  if (const auto v = corefined_volume(eb, es, true, mode))
    return std::max(0.0, (mode == Volume::Exact ? exact_volume(eb) : signed_volume(block)) - *v);
  return nef_volume_of(eb, es, NefBoolean::Difference);
}

}  // namespace

double blocks_overlap(const Mesh& a, const Mesh& b) { return overlap_volume(a, b, Volume::Rounded); }

double detail::exact_blocks_overlap(const Mesh& a, const Mesh& b) { return overlap_volume(a, b, Volume::Exact); }

double detail::exact_blocks_overlap(const Mesh& a, const Mesh& b, const BoundingBox& within) {
  return overlap_volume(a, b, Volume::Exact, &within);
}

double nef_boolean_volume(const Mesh& a, const Mesh& b, NefBoolean op) {
  require_boolean_input(a, "the first solid");
  require_boolean_input(b, "the second solid");
  return nef_volume_of(detail::to_exact(a), detail::to_exact(b), op);
}

double volume_outside(const Mesh& block, const Mesh& solid) { return outside_volume(block, solid, Volume::Rounded); }

double detail::exact_volume_outside(const Mesh& block, const Mesh& solid) {
  return outside_volume(block, solid, Volume::Exact);
}

namespace {

using EpickTree = CGAL::AABB_tree<CGAL::AABB_traits<
    CGAL::Exact_predicates_inexact_constructions_kernel,
    CGAL::AABB_triangle_primitive<CGAL::Exact_predicates_inexact_constructions_kernel,
                                  std::vector<CGAL::Exact_predicates_inexact_constructions_kernel::Triangle_3>::const_iterator>>>;

//! Whether the face (a, b, c), a face of a mesh corefined with `solid`,
//! lies on the solid's surface: its exact centroid lies on one of the
//! solid's faces (`tree` holds those near the block as doubles, face
//! triangles[i] is the solid's face ids[i]: candidates by box, then exact
//! tests).
bool lies_on_solid(const detail::ExactPoint& a, const detail::ExactPoint& b, const detail::ExactPoint& c,
                   const Mesh& solid, const EpickTree& tree,
                   const std::vector<CGAL::Exact_predicates_inexact_constructions_kernel::Triangle_3>& triangles,
                   const std::vector<int>& ids) {
  using EK = detail::ExactKernel;
  const EK::Point_3 m = CGAL::centroid(a, b, c);
  const CGAL::Bbox_3 box = m.bbox();
  std::vector<EpickTree::Primitive_id> hit;
  tree.all_intersected_primitives(box, std::back_inserter(hit));
  std::sort(hit.begin(), hit.end());  // face order: the same answer whatever the tree's order
  for (const auto& it : hit) {
    const Triangle& t = solid.faces[static_cast<std::size_t>(ids[static_cast<std::size_t>(it - triangles.begin())])];
    auto point = [&](int v) {
      const Vec3& q = solid.vertices[static_cast<std::size_t>(v)];
      return EK::Point_3(q.x(), q.y(), q.z());
    };
    if (EK::Triangle_3(point(t[0]), point(t[1]), point(t[2])).has_on(m)) return true;
  }
  return false;
}

//! The boolean of outside_part(), inside the caller's arena: fills `out`
//! (under a SuspendArena) or leaves it empty when the corefinement cannot
//! give a 2-manifold.
void outside_in_arena(const Mesh& block, const Mesh& solid, const BoundingBox* within, const EpickTree& tree,
                      const std::vector<CGAL::Exact_predicates_inexact_constructions_kernel::Triangle_3>& triangles,
                      const std::vector<int>& ids, std::optional<detail::OutsidePart>& out) {
  // The block, clipped to `within` when given (block \ solid lies inside
  // it): its faces far from the fill, most of them on the input's surface,
  // then never meet the solid's in the corefinement. Where the clip fails or
  // leaves nothing, the whole block.
  const auto exact_block = [&] {
    ExactMesh e = detail::to_exact(block);
    if (!within) return e;
    ExactMesh clipped = e;
    try {
      if (clip_to(clipped, *within) && clipped.number_of_faces() > 0) return clipped;
    } catch (const AlgorithmError&) {
    }
    return e;
  };
  ExactMesh eb = exact_block(), es = detail::to_exact(solid), d;
  if (PMP::corefine_and_compute_difference(eb, es, d, kThrowOnSelfIntersection, kThrowOnSelfIntersection)) {
    const double volume = std::max(0.0, mesh_volume(d));
    std::vector<char> on_input;
    on_input.reserve(d.number_of_faces());
    for (auto f : d.faces()) {  // the order of to_double()
      const auto h = d.halfedge(f);
      on_input.push_back(lies_on_solid(d.point(d.source(h)), d.point(d.target(h)), d.point(d.target(d.next(h))),
                                       solid, tree, triangles, ids));
    }
    detail::SuspendArena heap;
    out.emplace();
    out->volume = volume;
    out->mesh = detail::to_double(d);
    out->on_input.assign(on_input.begin(), on_input.end());  // a copy on the heap (on_input is in the arena)
    return;
  }
  // Not a 2-manifold: its faces, classified on eb and es as the failed
  // difference left them against the operands as given. Corefined: CGAL
  // 5.5's corefinement visitor splits and triangulates the intersected faces
  // of both inputs in place (Visitor.h, finalize()) before its output
  // builder finds that the result is not a 2-manifold.
  std::vector<ExactMesh> operands{std::move(eb), std::move(es)};
  const std::vector<ExactMesh> given{exact_block(), detail::to_exact(solid)};
  std::vector<std::pair<std::size_t, detail::FaceIndex>> kept;
  if (!detail::difference_surface(operands, given, kept)) return;
  std::map<detail::ExactPoint, int, detail::ExactPointLess> index;
  std::vector<detail::ExactPoint> points;
  std::vector<Triangle> faces;
  std::vector<char> on_input;
  for (const auto& [k, f] : kept) {
    const ExactMesh& m = operands[k];
    Triangle t{};
    int q = 0;
    for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) {
      const auto [it, added] = index.emplace(m.point(v), static_cast<int>(points.size()));
      if (added) points.push_back(m.point(v));
      if (q < 3) t[static_cast<std::size_t>(q)] = it->second;
      ++q;
    }
    if (k == 1) std::swap(t[1], t[2]);  // the input's faces, turned to face out of the difference
    faces.push_back(t);
    // the input's faces lie on it; the block's may (kept where the input lies on their other side)
    on_input.push_back(k == 1 || lies_on_solid(points[static_cast<std::size_t>(t[0])], points[static_cast<std::size_t>(t[1])],
                                               points[static_cast<std::size_t>(t[2])], solid, tree, triangles, ids));
  }
  // The volume bounded by the faces (closed, outward: the divergence theorem
  // holds for a non-manifold surface too), exact.
  const double volume = std::max(0.0, exact_volume_of([&](auto&& triangle) {
    for (const Triangle& t : faces)
      triangle(points[static_cast<std::size_t>(t[0])], points[static_cast<std::size_t>(t[1])],
               points[static_cast<std::size_t>(t[2])]);
  }));
  detail::SuspendArena heap;
  out.emplace();
  out->volume = volume;
  out->on_input.assign(on_input.begin(), on_input.end());  // a copy on the heap (on_input is in the arena)
  Mesh& soup = out->boundary.emplace();
  soup.faces = faces;
  soup.vertices.reserve(points.size());
  for (const detail::ExactPoint& p : points)  // each rounded once from its exact value
    soup.vertices.emplace_back(CGAL::to_double(CGAL::exact(p.x())), CGAL::to_double(CGAL::exact(p.y())),
                               CGAL::to_double(CGAL::exact(p.z())));
}

}  // namespace

detail::OutsidePart detail::outside_part(const Mesh& block, const Mesh& solid, const BoundingBox* within) {
  // the solid's faces near the block, for the classification of the part's faces
  using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
  BoundingBox near = bounding_box(block);
  near.min.array() -= 1e-9 * near.diagonal();
  near.max.array() += 1e-9 * near.diagonal();
  std::vector<Epick::Triangle_3> triangles;
  std::vector<int> ids;
  for (std::size_t f = 0; f < solid.faces.size(); ++f) {
    BoundingBox b;
    for (int v : solid.faces[f]) b.extend(solid.vertices[static_cast<std::size_t>(v)]);
    if (!detail::boxes_touch(b, near)) continue;
    auto point = [&](int v) {
      const Vec3& q = solid.vertices[static_cast<std::size_t>(v)];
      return Epick::Point_3(q.x(), q.y(), q.z());
    };
    triangles.emplace_back(point(solid.faces[f][0]), point(solid.faces[f][1]), point(solid.faces[f][2]));
    ids.push_back(static_cast<int>(f));
  }
  EpickTree tree(triangles.begin(), triangles.end());
  tree.build();  // now, outside the arena (CGAL builds it on the first query otherwise)
  if (!detail::interiors_meet(bounding_box(block), bounding_box(solid))) {
    OutsidePart whole{signed_volume(block), block, std::nullopt, {}};
    for (const Triangle& t : block.faces) {
      auto point = [&](int v) {
        const Vec3& q = block.vertices[static_cast<std::size_t>(v)];
        return detail::ExactPoint(q.x(), q.y(), q.z());
      };
      whole.on_input.push_back(lies_on_solid(point(t[0]), point(t[1]), point(t[2]), solid, tree, triangles, ids));
    }
    return whole;
  }
  require_boolean_input(block, "the block", true);
  require_boolean_input(solid, "the input");
  detail::warm_up_exact_booleans();
  std::optional<OutsidePart> out;
  // CGAL may refuse an operand (a self-intersection near the cut): the
  // fallback below reports it, outside the arena.
  // `within` is used only when it cuts the block (a plane of it inside the block's box)
  const BoundingBox own = bounding_box(block);
  const bool cuts = within && ((within->min.array() > own.min.array()).any() || (within->max.array() < own.max.array()).any());
  if (detail::run_in_arena([&] { outside_in_arena(block, solid, cuts ? within : nullptr, tree, triangles, ids, out); })
          .empty() &&
      out)
    return std::move(*out);
  return {volume_outside(block, solid), std::nullopt, std::nullopt, {}};
}

CoverageReport surface_coverage(const Mesh& input, const std::vector<const Mesh*>& blocks,
                                const CoverageOptions& options) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Tri = K::Triangle_3;
  using Primitive = CGAL::AABB_triangle_primitive<K, std::vector<Tri>::const_iterator>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

  CoverageReport r;
  r.tolerance = options.tolerance > 0 ? options.tolerance : 1e-5 * bounding_box(input).diagonal();
  std::vector<Tri> triangles;
  for (const Mesh* m : blocks)
    for (const Triangle& t : m->faces) {
      const Vec3& a = m->vertices[static_cast<std::size_t>(t[0])];
      const Vec3& b = m->vertices[static_cast<std::size_t>(t[1])];
      const Vec3& c = m->vertices[static_cast<std::size_t>(t[2])];
      Tri tri(K::Point_3(a.x(), a.y(), a.z()), K::Point_3(b.x(), b.y(), b.z()), K::Point_3(c.x(), c.y(), c.z()));
      if (!tri.is_degenerate()) triangles.push_back(tri);
    }
  // Samples: every vertex, then area-weighted random points (fixed seed).
  std::vector<Vec3> samples(input.vertices.begin(), input.vertices.end());
  std::vector<double> cumulative(input.num_faces());
  double total = 0.0;
  for (std::size_t f = 0; f < input.num_faces(); ++f) cumulative[f] = total += face_area(input, f);
  std::mt19937_64 rng(options.seed);
  auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  for (std::size_t s = 0; s < options.num_samples && total > 0; ++s) {
    const double x = uniform() * total;
    const std::size_t f = static_cast<std::size_t>(
        std::min<std::ptrdiff_t>(std::upper_bound(cumulative.begin(), cumulative.end(), x) - cumulative.begin(),
                                 static_cast<std::ptrdiff_t>(input.num_faces()) - 1));
    double u = uniform(), v = uniform();
    if (u + v > 1.0) {
      u = 1.0 - u;
      v = 1.0 - v;
    }
    const Triangle& t = input.faces[f];
    const Vec3& a = input.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = input.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = input.vertices[static_cast<std::size_t>(t[2])];
    samples.push_back(a + u * (b - a) + v * (c - a));
  }
  r.num_samples = samples.size();
  if (triangles.empty()) {
    r.num_uncovered = samples.size();
    r.max_distance = std::numeric_limits<double>::infinity();
    if (!samples.empty()) r.worst_point = samples.front();
    return r;
  }
  Tree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  for (const Vec3& p : samples) {
    const double d = std::sqrt(tree.squared_distance(K::Point_3(p.x(), p.y(), p.z())));
    if (d > r.tolerance) ++r.num_uncovered;
    if (d > r.max_distance) {
      r.max_distance = d;
      r.worst_point = p;
    }
  }
  return r;
}

}  // namespace subfab
