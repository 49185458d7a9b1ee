// SPDX-License-Identifier: GPL-3.0-or-later
// Warms up CGAL's per-thread lazy-exact objects before any arena (see
// warm_up_exact_booleans() in exact_mesh.h): used by carving and merging
// (thesis Section 4.3.3), whose exact booleans run in DeterministicArenas.
#include <CGAL/Polygon_mesh_processing/clip.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include "geometry/deterministic_arena.h"
#include "geometry/exact_mesh.h"
#include "geometry/union_surface.h"

namespace subfab::detail {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using FT = ExactKernel::FT;

Box3 make_box3(const Vec3& min, const Vec3& max) {
  Box3 b;
  b.min = min;
  b.max = max;
  return b;
}

ExactKernel::Iso_cuboid_3 to_cuboid(const Box3& b) {
  return {ExactPoint(b.min.x(), b.min.y(), b.min.z()), ExactPoint(b.max.x(), b.max.y(), b.max.z())};
}

}  // namespace

void warm_up_exact_booleans() {
  thread_local bool done = false;
  if (done) return;
  done = true;
  SuspendArena heap;  // in case an arena is active on this thread
  auto make = [](double x0, double y0, double z0, double x1, double y1, double z1) {
    return box_mesh(make_box3(Vec3(x0, y0, z0), Vec3(x1, y1, z1)));
  };
  {
    ExactMesh a = make(0, 0, 0, 2, 2, 1), b = make(0.5, 0.5, 0.5, 3, 3, 3), out;
    PMP::clip(a, to_cuboid(make_box3(Vec3(0, 0, 0), Vec3(1.5, 1.5, 1))), CGAL::parameters::clip_volume(true));
    PMP::corefine_and_compute_difference(a, b, out);
  }
  {
    ExactMesh a = make(0, 0, 0, 2, 2, 1), b = make(0.5, 0.5, 0.5, 3, 3, 3), out;
    PMP::corefine_and_compute_union(a, b, out);
    auto fcc = out.add_property_map<ExactMesh::Face_index, std::size_t>("f:cc", 0).first;
    PMP::connected_components(out, fcc);
    RoundingReport r;
    to_double(out, &r);
  }
  {
    ExactMesh a = make(0, 0, 0, 2, 2, 1), b = make(0.5, 0.5, 0.5, 3, 3, 3), out;
    PMP::corefine_and_compute_intersection(a, b, out);
  }
  {
    // A difference whose result is not manifold (two cubes sharing an edge).
    ExactMesh a = make(0, 0, 0, 2, 2, 1), b = make(0, 0, 0, 1, 1, 1), c = make(1, 1, 0, 2, 2, 1), ab, abc;
    if (PMP::corefine_and_compute_difference(a, b, ab)) PMP::corefine_and_compute_difference(ab, c, abc);
  }
  {
    // The overlay of union_surface(): two cubes sharing an edge, one sharing
    // a face with the first (Side_of_triangle_mesh's rays, the AABB tree's
    // point queries, the coplanar case).
    std::vector<ExactMesh> ops{make(0, 0, 0, 1, 1, 1), make(1, 1, 0, 2, 2, 1), make(0, 0, 1, 1, 1, 2)};
    std::vector<std::pair<std::size_t, FaceIndex>> kept;
    union_surface(ops, kept);
  }
  const ExactKernel::Triangle_3 t(ExactPoint(0, 0, 0), ExactPoint(1, 0, 0), ExactPoint(0, 1, 0));
  const ExactPoint c = CGAL::centroid(t[0], t[1], t[2]);
  (void)t.has_on(c);
  (void)(c.x() == FT(0.5));
  (void)CGAL::to_double(CGAL::exact(c.x()));
  ExactKernel::FT zero;
  ExactPoint origin;
  ExactKernel::Vector_3 v;
  ExactKernel::Plane_3 plane;
  ExactKernel::Segment_3 segment;
  ExactKernel::Iso_cuboid_3 cuboid;
  ExactKernel::Ray_3 ray;
  ExactKernel::Line_3 line;
  ExactKernel::Direction_3 direction;
  (void)ray;
  (void)line;
  (void)direction;
  (void)zero;
  (void)origin;
  (void)v;
  (void)plane;
  (void)segment;
  (void)cuboid;
}

}  // namespace subfab::detail
