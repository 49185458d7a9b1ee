// SPDX-License-Identifier: GPL-3.0-or-later
// measure_milled_shapes(): every block's milled shape (milled_shape.cpp) and
// how far it strays (CGAL bounded-error Hausdorff distances, exact booleans).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "subfab/core/parallel.h"
#include "subfab/validate/milled_shape.h"
#include "subfab/validate/validate_decomposition.h"
#include "geometry/box_tests.h"
#include "geometry/solid_index.h"
#include "geometry/surface_deviation.h"
#include "geometry/triangle_tree.h"
#include "validate/validate_booleans.h"

namespace subfab {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = detail::DistanceMesh;

//! Appends the faces of `m` (those listed in `faces`, all when null) whose
//! bounding box meets `reach` (all when it is empty) to the face graph `sm`
//! of the distance queries (geometry's append_distance_patch()).
void append(SurfaceMesh& sm, const Mesh& m, const std::vector<int>* faces = nullptr, const BoundingBox& reach = {}) {
  if (reach.is_empty()) return detail::append_distance_patch(sm, m, faces);
  std::vector<int> near;
  auto keep = [&](int f) {
    BoundingBox fb;
    for (int v : m.faces[static_cast<std::size_t>(f)]) fb.extend(m.vertices[static_cast<std::size_t>(v)]);
    if (detail::boxes_touch(fb, reach)) near.push_back(f);
  };
  if (faces)
    for (int f : *faces) keep(f);
  else
    for (std::size_t f = 0; f < m.num_faces(); ++f) keep(static_cast<int>(f));
  detail::append_distance_patch(sm, m, &near);
}

//! Area of the part of triangle `t` covered by triangle `f`, both given by
//! 2D corners (t counter-clockwise; f counter-clockwise too, else 0).
double covered_area(const std::array<Eigen::Vector2d, 3>& t, const std::array<Eigen::Vector2d, 3>& f) {
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
  if (cross(f[1] - f[0], f[2] - f[0]) <= 0.0) return 0.0;
  std::vector<Eigen::Vector2d> poly(t.begin(), t.end()), next;
  for (int k = 0; k < 3 && !poly.empty(); ++k) {  // Sutherland-Hodgman: keep the left of each edge of f
    const Eigen::Vector2d &p = f[static_cast<std::size_t>(k)], &q = f[static_cast<std::size_t>((k + 1) % 3)];
    auto side = [&](const Eigen::Vector2d& x) { return cross(q - p, x - p); };
    next.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector2d &a = poly[i], &b = poly[(i + 1) % poly.size()];
      const double sa = side(a), sb = side(b);
      if (sa >= 0) next.push_back(a);
      if ((sa >= 0) != (sb >= 0)) next.push_back(a + (b - a) * (sa / (sa - sb)));
    }
    poly.swap(next);
  }
  double area = 0.0;
  for (std::size_t i = 1; i + 1 < poly.size(); ++i) area += cross(poly[i] - poly[0], poly[i + 1] - poly[0]);
  return 0.5 * area;
}

//! The wall and base faces of `milled` that are not covered by faces of the
//! block lying in their plane (within `tolerance`, model units): the only
//! faces whose distance to the block can be more than a rounding error (the
//! top faces lie on the block's faces by construction). A face counts as
//! covered when the block's faces in its plane cover all but 1e-9 of its
//! area (sliver gaps from rounding; the points of such a gap are within its
//! width of the block).
std::vector<int> uncovered_faces(const MilledShape& milled, const Mesh& block, double tolerance) {
  const Mesh& m = milled.mesh;
  std::vector<BoundingBox> block_boxes(block.num_faces());
  std::vector<Vec3> block_normals(block.num_faces());
  for (std::size_t f = 0; f < block.num_faces(); ++f) {
    for (int v : block.faces[f]) block_boxes[f].extend(block.vertices[static_cast<std::size_t>(v)]);
    block_normals[f] = face_unit_normal(block, f);
  }
  std::vector<int> out;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    if (milled.face_kinds[f] == MilledFaceKind::Top) continue;
    const Vec3 n = face_unit_normal(m, f);
    const std::array<Vec3, 3> c{m.vertices[static_cast<std::size_t>(m.faces[f][0])],
                                m.vertices[static_cast<std::size_t>(m.faces[f][1])],
                                m.vertices[static_cast<std::size_t>(m.faces[f][2])]};
    const double area = face_area(m, f);
    if (area <= 0.0 || n.squaredNorm() == 0.0) continue;  // a rounding-degenerate face: nothing to measure
    BoundingBox box;
    for (const Vec3& p : c) box.extend(p);
    box.min.array() -= tolerance;
    box.max.array() += tolerance;
    const Vec3 u = (c[1] - c[0]).normalized(), w = n.cross(u);
    auto in_plane = [&](const Vec3& p) { return Eigen::Vector2d((p - c[0]).dot(u), (p - c[0]).dot(w)); };
    const std::array<Eigen::Vector2d, 3> t2{in_plane(c[0]), in_plane(c[1]), in_plane(c[2])};
    double covered = 0.0;
    for (std::size_t g = 0; g < block.num_faces(); ++g) {
      if (!detail::boxes_touch(block_boxes[g], box) || block_normals[g].dot(n) <= 0.0) continue;
      const std::array<Vec3, 3> d{block.vertices[static_cast<std::size_t>(block.faces[g][0])],
                                  block.vertices[static_cast<std::size_t>(block.faces[g][1])],
                                  block.vertices[static_cast<std::size_t>(block.faces[g][2])]};
      bool coplanar = true;
      for (const Vec3& p : d) coplanar = coplanar && std::abs((p - c[0]).dot(n)) <= tolerance;
      for (const Vec3& p : c) coplanar = coplanar && std::abs((p - d[0]).dot(block_normals[g])) <= tolerance;
      if (coplanar) covered += covered_area(t2, {in_plane(d[0]), in_plane(d[1]), in_plane(d[2])});
    }
    if (covered < (1.0 - 1e-9) * area) out.push_back(static_cast<int>(f));
  }
  return out;
}

//! The box around `box` within `margin` of it.
BoundingBox widened(BoundingBox box, double margin) {
  box.min.array() -= margin;
  box.max.array() += margin;
  return box;
}

//! The farthest a point of given faces lies outside a closed solid, from
//! its surface: sup over the faces of g(x) = d(x, surface) if x is outside,
//! 0 inside (g is 1-Lipschitz). Branch and bound over 1-to-4 subdivisions,
//! deterministic (a function of the meshes only): a triangle is dropped when
//! an upper bound of g on it (the Lipschitz bound from its corners; the
//! distance to one surface triangle, convex, so bounded by its corners'; 0
//! when it is inside and farther from the surface than its size) is within
//! `error` of the best value found. Inside/outside is exact (SolidIndex).
class OutsideDistance {
 public:
  explicit OutsideDistance(const Mesh& solid) : index_(solid), surface_(solid) {
    surface_.accelerate_distance_queries();  // before any concurrent query
  }

  double sup(const Mesh& m, const std::vector<int>& faces, double error) const {
    struct Corner {
      Vec3 p;
      double distance;  // to the surface
      bool inside;
      std::size_t face;  // nearest surface triangle
    };
    auto corner = [&](const Vec3& p) {
      const auto [q, it] = surface_.tree().closest_point_and_primitive(point(p));
      return Corner{p, std::sqrt(CGAL::squared_distance(point(p), q)), index_.is_inside(p),
                    static_cast<std::size_t>(it - surface_.triangles().begin())};
    };
    auto g = [](const Corner& c) { return c.inside ? 0.0 : c.distance; };
    double best = 0.0;
    std::vector<std::array<Corner, 3>> stack;
    for (int f : faces) {
      std::array<Corner, 3> t;
      for (std::size_t k = 0; k < 3; ++k) {
        t[k] = corner(m.vertices[static_cast<std::size_t>(m.faces[static_cast<std::size_t>(f)][k])]);
        best = std::max(best, g(t[k]));
      }
      stack.push_back(t);
    }
    while (!stack.empty()) {
      const std::array<Corner, 3> t = stack.back();
      stack.pop_back();
      double longest = 0.0, near = std::numeric_limits<double>::infinity(), bound = 0.0;
      bool inside = true;
      for (std::size_t k = 0; k < 3; ++k) {
        longest = std::max(longest, (t[k].p - t[(k + 1) % 3].p).norm());
        near = std::min(near, t[k].distance);
        bound = std::max(bound, g(t[k]));
        inside = inside && t[k].inside;
      }
      const double reach = 0.578 * longest;  // every point of t is this close to a corner (> edge / sqrt 3)
      if (inside && near > reach) continue;  // no surface point in t: all of it inside
      bound += reach;
      for (const Corner& c : t) {  // distance to one surface triangle is convex: its max is at a corner
        double d = 0.0;
        for (const Corner& k : t) d = std::max(d, std::sqrt(CGAL::squared_distance(point(k.p), surface_.triangles()[c.face])));
        bound = std::min(bound, d);
      }
      if (bound <= best + error) continue;
      const Corner ab = corner(0.5 * (t[0].p + t[1].p)), bc = corner(0.5 * (t[1].p + t[2].p)),
                   ca = corner(0.5 * (t[2].p + t[0].p));
      best = std::max({best, g(ab), g(bc), g(ca)});
      stack.push_back({t[0], ab, ca});
      stack.push_back({ab, t[1], bc});
      stack.push_back({ca, bc, t[2]});
      stack.push_back({ab, bc, ca});
    }
    return best;
  }

 private:
  static Epick::Point_3 point(const Vec3& p) { return detail::TriangleTree::point(p); }
  detail::SolidIndex index_;
  detail::TriangleTree surface_;
};

//! Measures of one non-exact block.
void measure_block(const Mesh& input, const OutsideDistance& outside, const Mesh& block, const MilledShape& milled,
                   double error, double plane_tolerance, MilledShapeMeasures& m) {
  // Only the faces off the block's surface can be far from it; every point
  // of the milled surface is within the diagonal of its box of the block, so
  // input faces farther than that never matter.
  const std::vector<int> off_block = uncovered_faces(milled, block, plane_tolerance);
  if (!off_block.empty()) {
    SurfaceMesh source, to_block, to_both;
    append(source, milled.mesh, &off_block);
    append(to_block, block);
    const BoundingBox box = bounding_box(milled.mesh);
    append(to_both, input, nullptr, widened(box, box.diagonal() + error));
    append(to_both, block);
    m.deviation_to_block = detail::one_sided_hausdorff(source, to_block, error);
    m.deviation = detail::one_sided_hausdorff(source, to_both, error);
  }
  m.outside_volume = detail::exact_volume_outside(milled.mesh, input);
  m.outside_distance = outside.sup(milled.mesh, off_block, error);
}

}  // namespace

std::size_t MilledShapesReport::num_exact() const {
  return static_cast<std::size_t>(std::count_if(blocks.begin(), blocks.end(), [](const auto& b) { return b.exact; }));
}

double MilledShapesReport::max_deviation() const {
  double d = 0.0;
  for (const MilledShapeMeasures& b : blocks) d = std::max(d, b.deviation);
  return d;
}

double MilledShapesReport::total_filled_volume() const {
  double v = 0.0;
  for (const MilledShapeMeasures& b : blocks) v += b.filled_volume;
  return v;
}

namespace {

//! Each block's milled shape and measures (parallel over blocks): fills
//! report.blocks, returns the milled shapes of the non-exact blocks.
std::vector<MilledShape> measure_each_block(const Mesh& input, const std::vector<MilledBlockInput>& blocks,
                                            const MilledMeasureOptions& options, double plane_tolerance,
                                            MilledShapesReport& report) {
  std::vector<MilledShape> milled(blocks.size());
  std::unique_ptr<OutsideDistance> outside;  // built for the first non-exact block
  std::once_flag outside_built;
  StageScope stage(options.progress, "milled shapes");
  std::atomic<std::size_t> done{0};
  parallel_for(0, blocks.size(), [&](std::size_t i) {
    const MilledBlockInput& b = blocks[i];
    MilledShapeMeasures& m = report.blocks[i];
    m.block_volume = signed_volume(*b.mesh);
    try {
      MilledShape s = milled_shape(*b.mesh, b.direction,
                                   {.normal_tolerance = options.normal_tolerance,
                                    .plane_tolerance = plane_tolerance,
                                    .frame = b.frame});
      m.exact = s.is_block;
      m.num_faces = s.mesh.num_faces();
      m.volume = m.exact ? m.block_volume : signed_volume(s.mesh);
      m.filled_volume = m.volume - m.block_volume;
      if (!m.exact) milled[i] = std::move(s);
    } catch (const std::exception& e) {
      m.exact = false;
      m.error = std::string("milled shape failed: ") + e.what();
    }
    if (!m.exact && m.error.empty()) {
      try {
        std::call_once(outside_built, [&] { outside = std::make_unique<OutsideDistance>(input); });
        measure_block(input, *outside, *b.mesh, milled[i], report.hausdorff_error, plane_tolerance, m);
      } catch (const std::exception& e) {
        m.error = std::string("measure failed: ") + e.what();
      }
    }
    if (options.progress) options.progress->update(++done, blocks.size());
  });
  return milled;
}

//! Collisions: pairs with a non-exact block whose boxes overlap and whose
//! overlap bound (input frame, either block's frame) does not settle them
//! get an exact intersection volume.
void find_collisions(const std::vector<MilledBlockInput>& blocks, const std::vector<MilledShape>& milled,
                     const MilledMeasureOptions& options, MilledShapesReport& report) {
  const std::size_t n = blocks.size();
  const auto shape = [&](std::size_t i) -> const Mesh& {
    return report.blocks[i].exact || milled[i].mesh.faces.empty() ? *blocks[i].mesh : milled[i].mesh;
  };
  std::vector<BoundingBox> boxes(n);
  std::vector<double> volumes(n);
  for (std::size_t i = 0; i < n; ++i) {
    boxes[i] = bounding_box(shape(i));
    volumes[i] = std::abs(signed_volume(shape(i)));
  }
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if ((!report.blocks[i].exact || !report.blocks[j].exact) &&
          (boxes[i].min.array() < boxes[j].max.array()).all() && (boxes[j].min.array() < boxes[i].max.array()).all())
        pairs.emplace_back(i, j);
  report.num_pairs_checked = pairs.size();
  std::vector<double> overlap(pairs.size(), 0.0);
  std::vector<std::string> errors(pairs.size());
  StageScope stage(options.progress, "milled-shape collisions");
  std::atomic<std::size_t> done{0};
  parallel_for(0, pairs.size(), [&](std::size_t p) {
    const auto [i, j] = pairs[p];
    const Mesh &a = shape(i), &b = shape(j);
    double bound = overlap_volume_bound(a, b, Eigen::Matrix3d::Identity());
    for (std::size_t k : {i, j})
      if (blocks[k].frame) bound = std::min(bound, overlap_volume_bound(a, b, *blocks[k].frame));
    if (bound > options.collision_tolerance * std::min(volumes[i], volumes[j])) {
      try {
        overlap[p] = detail::exact_blocks_overlap(a, b);
      } catch (const std::exception& e) {
        errors[p] = e.what();
      }
    }
    if (options.progress) options.progress->update(++done, pairs.size());
  });
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto [i, j] = pairs[p];
    if (!errors[p].empty()) {
      for (std::size_t k : {i, j})
        if (report.blocks[k].error.empty()) report.blocks[k].error = "collision test failed: " + errors[p];
      continue;
    }
    if (overlap[p] > options.collision_tolerance * std::min(volumes[i], volumes[j]))
      report.collisions.push_back({i, j, overlap[p]});
  }
}

}  // namespace

MilledShapesReport measure_milled_shapes(const Mesh& input, const std::vector<MilledBlockInput>& blocks,
                                         const MilledMeasureOptions& options) {
  const double diagonal = bounding_box(input).diagonal();
  MilledShapesReport report;
  report.hausdorff_error = options.hausdorff_error * diagonal;
  report.blocks.resize(blocks.size());
  const std::vector<MilledShape> milled =
      measure_each_block(input, blocks, options, 1e-9 * std::max(1.0, diagonal), report);
  find_collisions(blocks, milled, options, report);
  return report;
}

}  // namespace subfab
