// SPDX-License-Identifier: GPL-3.0-or-later
// Moving box faces off the contacts no axis-aligned cut separated (thesis
// Section 4.3.3, carving), see contact_mover.h.
#include "decompose/contact_mover.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "geometry/exact_determinant_signs.h"
#include "geometry/triangle_meets_closed_box.h"
#include "subfab/geometry/axis.h"

namespace subfab::detail {

std::vector<Box3> ContactMover::candidates(const BoxFace& f) {
  const HeightBox& hb = boxes_[f.box];
  int& count = num_tried_[f];
  const double step = step_ * std::pow(10.0, count);
  ++count;
  const double at = f.side < 0 ? hb.box.min[f.k] : hb.box.max[f.k];
  std::vector<Box3> out;
  for (int sense : {1, -1}) {
    Box3 moved = hb.box;
    double& c = f.side < 0 ? moved.min[f.k] : moved.max[f.k];
    c = at + sense * f.side * step;
    const bool ok = sense > 0 ? box_fits_limits(moved, hb.axis, options_.max_height, options_.machine_size) &&
                                    index_.box_is_valid(moved, hb.axis)
                              : moved.min[f.k] < moved.max[f.k] && keeps_coverage(f, moved);
    if (ok) out.push_back(moved);
  }
  return out;
}

void ContactMover::apply(const BoxFace& f, const Box3& moved, std::vector<char>& dirty) {
  HeightBox& hb = boxes_[f.box];
  Box3 hull = hb.box;
  hull.min = hull.min.cwiseMin(moved.min);
  hull.max = hull.max.cwiseMax(moved.max);
  hb.box = moved;
  ++num_moves_;
  for (std::size_t j = f.box; j < boxes_.size(); ++j)
    if (j == f.box || boxes_[j].box.overlaps(hull)) dirty[j] = 1;
}

void ContactMover::undo(const BoxFace& f, const HeightBox& before) {
  boxes_[f.box] = before;
  --num_moves_;
}

bool ContactMover::keeps_coverage(const BoxFace& f, const Box3& shrunk) const {
  const Box3& old = boxes_[f.box].box;
  Box3 slab = old;
  if (f.side < 0)
    slab.max[f.k] = shrunk.min[f.k];
  else
    slab.min[f.k] = shrunk.max[f.k];
  const Mesh& mesh = index_.mesh();
  for (int face : index_.faces_near_closed_box(slab)) {
    const Triangle& t = mesh.faces[static_cast<std::size_t>(face)];
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    if (!detail::triangle_meets_closed_box(a, b, c, slab)) continue;
    Box3 part = slab;
    part.min = part.min.cwiseMax(index_.face_box(face).min);
    part.max = part.max.cwiseMin(index_.face_box(face).max);
    if (!part_is_held(part, a, b, c, f.box, shrunk)) return false;
  }
  return true;
}

bool ContactMover::part_is_held(const Box3& part, const Vec3& a, const Vec3& b, const Vec3& c, std::size_t skip,
                                const Box3& replacement) const {
  auto box_at = [&](std::size_t j) -> const Box3& { return j == skip ? replacement : boxes_[j].box; };
  std::array<std::vector<double>, 3> planes;
  for (int k = 0; k < 3; ++k) {
    auto& p = planes[static_cast<std::size_t>(k)];
    p = {part.min[k], part.max[k]};
    for (std::size_t j = 0; j < boxes_.size(); ++j)
      for (double v : {box_at(j).min[k], box_at(j).max[k]})
        if (v > part.min[k] && v < part.max[k]) p.push_back(v);
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
  }
  // The dimensions the triangle lies flat in, and its normal's sign there.
  std::array<int, 3> flat_sign{};
  for (int k = 0; k < 3; ++k)
    if (a[k] == b[k] && a[k] == c[k]) flat_sign[static_cast<std::size_t>(k)] = detail::normal_component_sign(a, b, c, k);
  auto cell_count = [&](int k) { return std::max<std::size_t>(1, planes[static_cast<std::size_t>(k)].size() - 1); };
  auto coordinate = [&](int k, std::size_t i) {
    const auto& p = planes[static_cast<std::size_t>(k)];
    return p.size() == 1 ? p[0] : 0.5 * (p[i] + p[i + 1]);
  };
  for (std::size_t ix = 0; ix < cell_count(0); ++ix)
    for (std::size_t iy = 0; iy < cell_count(1); ++iy)
      for (std::size_t iz = 0; iz < cell_count(2); ++iz) {
        const Vec3 q(coordinate(0, ix), coordinate(1, iy), coordinate(2, iz));
        bool held = false;
        for (std::size_t j = 0; j < boxes_.size() && !held; ++j) {
          const Box3& h = box_at(j);
          held = (q.array() >= h.min.array()).all() && (q.array() <= h.max.array()).all();
          for (int k = 0; k < 3 && held; ++k) {
            const int s = flat_sign[static_cast<std::size_t>(k)];
            if (q[k] == h.min[k] && s != -1) held = false;
            if (q[k] == h.max[k] && s != 1) held = false;
          }
        }
        if (!held) return false;
      }
  return true;
}

}  // namespace subfab::detail
