// SPDX-License-Identifier: GPL-3.0-or-later
#include "hex/surface_projector.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <vector>

#include "geometry/solid_index.h"

namespace subfab::detail {

namespace {
using K = CGAL::Simple_cartesian<double>;
using Point = K::Point_3;
using Triangle3 = K::Triangle_3;
using Iterator = std::vector<Triangle3>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, Iterator>;
using Traits = CGAL::AABB_traits<K, Primitive>;
using Tree = CGAL::AABB_tree<Traits>;

Point to_point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
Vec3 to_vec(const Point& p) { return {p.x(), p.y(), p.z()}; }
}  // namespace

struct SurfaceProjector::Impl {
  explicit Impl(const Mesh& surface) : solid(surface) {}
  std::vector<Triangle3> triangles;
  Tree tree;
  SolidIndex solid;  // exact inside/outside
};

SurfaceProjector::SurfaceProjector(const Mesh& surface) : impl_(std::make_unique<Impl>(surface)) {
  for (const Triangle& t : surface.faces)
    impl_->triangles.emplace_back(to_point(surface.vertices[static_cast<std::size_t>(t[0])]),
                                  to_point(surface.vertices[static_cast<std::size_t>(t[1])]),
                                  to_point(surface.vertices[static_cast<std::size_t>(t[2])]));
  impl_->tree.insert(impl_->triangles.begin(), impl_->triangles.end());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

SurfaceProjector::~SurfaceProjector() = default;

Vec3 SurfaceProjector::closest_point(const Vec3& p, Vec3* normal) const {
  const auto [point, it] = impl_->tree.closest_point_and_primitive(to_point(p));
  if (normal) {
    const K::Vector_3 n = CGAL::normal(it->vertex(0), it->vertex(1), it->vertex(2));
    *normal = Vec3(n.x(), n.y(), n.z()).normalized();
  }
  return to_vec(point);
}

std::optional<Vec3> SurfaceProjector::first_hit(const Vec3& origin, const Vec3& direction) const {
  const K::Ray_3 ray(to_point(origin), K::Vector_3(direction.x(), direction.y(), direction.z()));
  std::vector<Tree::Intersection_and_primitive_id<K::Ray_3>::Type> hits;
  impl_->tree.all_intersections(ray, std::back_inserter(hits));
  std::optional<Vec3> best;
  double best_d = 1e300;
  for (const auto& [object, id] : hits)
    if (const Point* q = boost::get<Point>(&object)) {  // segment overlaps (grazing rays) are ignored
      const double d = (to_vec(*q) - origin).squaredNorm();
      if (d < best_d) best_d = d, best = to_vec(*q);
    }
  return best;
}

bool SurfaceProjector::inside(const Vec3& p) const {
  // exact, with a definite answer on the surface (simulation of simplicity;
  // a ray through an edge or a vertex, e.g. at the centre of the symmetric Y
  // test shape, is no special case)
  return impl_->solid.is_inside(p);
}

}  // namespace subfab::detail
