// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/validate/fill_deviation_lower_bound.h"

#include <CGAL/squared_distance_3.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "geometry/box_tests.h"
#include "geometry/solid_index.h"
#include "geometry/triangle_tree.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "validate/lazy_solid.h"

namespace subfab {
namespace {

bool box_contains(const BoundingBox& b, const Vec3& p, double slack) {
  return (p.array() >= b.min.array() - slack).all() && (p.array() <= b.max.array() + slack).all();
}

constexpr int kSteps = 4;  // barycentric grid of step 1/4: 15 points per face

//! Calls visit(p) for the grid points of triangle abc while keep_going().
template <typename Visit, typename KeepGoing>
void for_each_sample(const Vec3& a, const Vec3& b, const Vec3& c, const Visit& visit, const KeepGoing& keep_going) {
  for (int i = 0; i <= kSteps && keep_going(); ++i)
    for (int j = 0; i + j <= kSteps && keep_going(); ++j) {
      const double u = static_cast<double>(i) / kSteps, v = static_cast<double>(j) / kSteps;
      visit(Vec3((1 - u - v) * a + u * b + v * c));
    }
}

}  // namespace

std::vector<double> fill_deviation_lower_bounds(const Mesh& solid, const std::vector<const Mesh*>& filled,
                                                const std::vector<std::optional<std::vector<BoundingBox>>>& fills,
                                                double stop, const std::vector<char>& which,
                                                std::vector<std::vector<Vec3>>* far) {
  const std::size_t n = filled.size();
  if (fills.size() != n || (!which.empty() && which.size() != n))
    throw InvalidArgumentError("fill_deviation_lower_bounds: one fill and one flag per filled block expected");
  std::vector<double> bound(n, 0.0);
  if (far) far->assign(n, {});
  if (n == 0 || solid.faces.empty()) return bound;
  const detail::SolidIndex inside(solid);
  detail::TriangleTree surface(solid);
  surface.accelerate_distance_queries();  // before the concurrent queries
  std::vector<BoundingBox> boxes(n);
  double scale = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    boxes[k] = bounding_box(*filled[k]);
    if (!boxes[k].is_empty()) scale = std::max({scale, boxes[k].min.cwiseAbs().maxCoeff(), boxes[k].max.cwiseAbs().maxCoeff()});
  }
  const double contact = 1e-7 * std::max(scale, 1e-300);  // on another fill's surface
  std::vector<detail::LazySolid> others(n);
  parallel_for(0, n, [&](std::size_t k) {
    if (!which.empty() && !which[k]) return;
    const Mesh& m = *filled[k];
    double best = 0.0;
    std::vector<Vec3>* out = far ? &(*far)[k] : nullptr;
    const auto not_done = [&] { return out || !(best > stop); };
    // a sample is worth the exact tests when it raises the bound or, when
    // collecting, lies beyond `stop`
    const auto worth = [&](double d) { return d > best || (out && d > stop); };
    const auto found = [&](double d, const Vec3& p) {
      best = std::max(best, d);
      if (out && d > stop) out->push_back(p);
    };
    for (std::size_t f = 0; f < m.faces.size() && not_done(); ++f) {
      const Vec3& a = m.vertices[static_cast<std::size_t>(m.faces[f][0])];
      const Vec3& b = m.vertices[static_cast<std::size_t>(m.faces[f][1])];
      const Vec3& c = m.vertices[static_cast<std::size_t>(m.faces[f][2])];
      if (fills[k]) {
        BoundingBox fb;
        fb.extend(a);
        fb.extend(b);
        fb.extend(c);
        const auto meets = [&](const BoundingBox& x) { return detail::boxes_touch(fb, x); };
        if (std::none_of(fills[k]->begin(), fills[k]->end(), meets)) continue;
      }
      for_each_sample(
          a, b, c,
          [&](const Vec3& p) {
            const auto q = detail::TriangleTree::point(p);
            const double d = std::sqrt(CGAL::squared_distance(q, surface.tree().closest_point(q)));
            if (!worth(d) || inside.is_inside(p)) return;
            for (std::size_t j = 0; j < n; ++j) {
              if (j == k || !box_contains(boxes[j], p, contact)) continue;
              others[j].build(*filled[j]);
              const double e = std::sqrt(CGAL::squared_distance(q, others[j].surface->tree().closest_point(q)));
              if (e <= contact || others[j].index->is_inside(p)) return;  // on or in another fill
            }
            found(d, p);
          },
          not_done);
    }
    // The other way: a point x of ∂S inside F_k is at least d(x, ∂F_k) from
    // ∂S' (the open ball of that radius lies in F_k, so in the interior of S').
    if (not_done()) {
      others[k].build(m);
      const detail::SolidIndex& in_block = *others[k].index;
      const detail::TriangleTree& block_surface = *others[k].surface;
      std::vector<CGAL::Bbox_3> regions;
      if (fills[k]) {
        for (const BoundingBox& x : *fills[k])
          regions.emplace_back(x.min.x(), x.min.y(), x.min.z(), x.max.x(), x.max.y(), x.max.z());
      } else {
        regions.emplace_back(boxes[k].min.x(), boxes[k].min.y(), boxes[k].min.z(), boxes[k].max.x(),
                             boxes[k].max.y(), boxes[k].max.z());
      }
      std::vector<std::size_t> faces;
      for (const CGAL::Bbox_3& r : regions) {
        std::vector<detail::TriangleTree::Iterator> hit;
        surface.tree().all_intersected_primitives(r, std::back_inserter(hit));
        for (const auto& it : hit) faces.push_back(static_cast<std::size_t>(it - surface.triangles().begin()));
      }
      std::sort(faces.begin(), faces.end());
      faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
      for (std::size_t f : faces) {
        if (!not_done()) break;
        const Vec3& a = solid.vertices[static_cast<std::size_t>(solid.faces[f][0])];
        const Vec3& b = solid.vertices[static_cast<std::size_t>(solid.faces[f][1])];
        const Vec3& c = solid.vertices[static_cast<std::size_t>(solid.faces[f][2])];
        for_each_sample(
            a, b, c,
            [&](const Vec3& p) {
              const auto q = detail::TriangleTree::point(p);
              const double d = std::sqrt(CGAL::squared_distance(q, block_surface.tree().closest_point(q)));
              if (worth(d) && in_block.is_inside(p)) found(d, p);
            },
            not_done);
      }
    }
    bound[k] = best;
  });
  return bound;
}

}  // namespace subfab
