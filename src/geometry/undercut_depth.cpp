// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/undercut_depth.h"

#include "geometry/triangle_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace subfab::detail {
namespace {
using Epick = TriangleTree::Kernel;
Epick::Point_3 point(const Vec3& p) { return TriangleTree::point(p); }
}  // namespace

struct UndercutDepth::Impl {
  explicit Impl(const Mesh& m) : mesh(m), surface(m) {}
  Mesh mesh;
  TriangleTree surface;
};

UndercutDepth::UndercutDepth(const Mesh& mesh) : impl_(std::make_unique<Impl>(mesh)) {
  impl_->surface.accelerate_distance_queries();  // builds the tree now, so const queries are thread-safe
}

UndercutDepth::~UndercutDepth() = default;

const Mesh& UndercutDepth::mesh() const { return impl_->mesh; }

double UndercutDepth::depth(std::size_t face, const Vec3& d, double cap, double limit) const {
  const Impl& m = *impl_;
  const Triangle& t = m.mesh.faces[face];
  const Vec3& a = m.mesh.vertices[static_cast<std::size_t>(t[0])];
  const Vec3& b = m.mesh.vertices[static_cast<std::size_t>(t[1])];
  const Vec3& c = m.mesh.vertices[static_cast<std::size_t>(t[2])];
  const Vec3 n = (b - a).cross(c - a);
  const double length = n.norm();
  if (!(length > 0)) return 0.0;
  const double cosine = -n.dot(d) / length;
  if (!(cosine > 0)) return 0.0;
  if (!(cap > 0)) return 0.0;
  if (cap * cosine <= limit) return cap * cosine;
  const Vec3 centroid = (a + b + c) / 3.0;
  const std::array<Vec3, 4> samples{centroid, 0.8 * a + 0.2 * centroid, 0.8 * b + 0.2 * centroid,
                                    0.8 * c + 0.2 * centroid};
  const auto self = m.surface.triangles().begin() + static_cast<std::ptrdiff_t>(face);
  const auto skip = [self](TriangleTree::Iterator id) { return id == self; };
  double free = 0.0;
  for (const Vec3& p : samples) {
    double reach = cap;
    const Epick::Ray_3 ray(point(p), Epick::Direction_3(-d.x(), -d.y(), -d.z()));
    if (const auto hit = m.surface.tree().first_intersection(ray, skip)) {
      if (const Epick::Point_3* q = boost::get<Epick::Point_3>(&hit->first))
        reach = std::min(reach, std::sqrt(CGAL::squared_distance(*q, point(p))));
      else
        reach = 0.0;  // the ray runs along a face: the surface is right there
    }
    free = std::max(free, reach);
  }
  return free * cosine;
}

}  // namespace subfab::detail
