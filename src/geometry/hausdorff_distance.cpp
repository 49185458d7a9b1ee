// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/hausdorff_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/triangle_tree.h"
#include "subfab/core/parallel.h"

namespace subfab::detail {

namespace {

// Largest distance from samples of `from` to the surface of `to`.
double one_sided(const Mesh& from, const Mesh& to, std::size_t samples) {
  TriangleTree surface(to);
  surface.accelerate_distance_queries();
  const TriangleTree::Tree& tree = surface.tree();
  const double area = surface_area(from);
  const double cell = area > 0 ? area / static_cast<double>(std::max<std::size_t>(samples, 1)) : 1.0;
  std::vector<double> worst(from.faces.size(), 0.0);
  parallel_for(0, from.faces.size(), [&](std::size_t t) {
    const auto& f = from.faces[t];
    const Vec3 &a = from.vertices[f[0]], &b = from.vertices[f[1]], &c = from.vertices[f[2]];
    const double tri_area = 0.5 * (b - a).cross(c - a).norm();
    const double steps = std::ceil(std::sqrt(tri_area / cell));
    const int n = !(steps > 1) ? 1 : (steps >= 64 ? 64 : static_cast<int>(steps));
    double w = 0;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const double u = double(i) / n, v = double(j) / n;
        const Vec3 p = a + u * (b - a) + v * (c - a);
        w = std::max(w, std::sqrt(CGAL::to_double(tree.squared_distance(TriangleTree::point(p)))));
      }
    worst[t] = w;
  }, 64);
  return worst.empty() ? 0.0 : *std::max_element(worst.begin(), worst.end());
}

}  // namespace

struct SurfaceDistance::Impl {
  explicit Impl(const Mesh& mesh) : surface(mesh) {}
  TriangleTree surface;
};

SurfaceDistance::SurfaceDistance(const Mesh& mesh) : impl_(std::make_unique<Impl>(mesh)) {
  impl_->surface.accelerate_distance_queries();
}

SurfaceDistance::~SurfaceDistance() = default;

double SurfaceDistance::operator()(const Vec3& p) const {
  if (impl_->surface.triangles().empty()) return std::numeric_limits<double>::infinity();
  return std::sqrt(CGAL::to_double(impl_->surface.tree().squared_distance(TriangleTree::point(p))));
}

double hausdorff_distance(const Mesh& a, const Mesh& b, std::size_t samples_per_mesh) {
  if (a.faces.empty() || b.faces.empty()) return a.faces.empty() && b.faces.empty() ? 0.0 : std::numeric_limits<double>::infinity();
  return std::max(one_sided(a, b, samples_per_mesh), one_sided(b, a, samples_per_mesh));
}

}  // namespace subfab::detail
