// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_self_intersections.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <string>
#include <utility>

#include "checks/edge_topology.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {

using namespace checks_detail;

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using Triangle3 = Kernel::Triangle_3;
using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, const Triangle*>;
using FacePair = std::pair<std::uint32_t, std::uint32_t>;

// Candidate pairs are tested in batches of this size, which bounds the memory
// even when many bounding boxes overlap.
constexpr std::size_t kBatch = 1 << 20;
// Below this many boxes the box intersection compares all pairs directly
// (CGAL's own self-intersection code uses the same value; 5x faster than the
// default of 10 on the 56k-face bunny).
constexpr std::ptrdiff_t kBoxCutoff = 2000;

Point point(const Mesh& mesh, int v) {
  const Vec3& p = mesh.vertices[static_cast<std::size_t>(v)];
  return {p.x(), p.y(), p.z()};
}

//! True when faces f and g intersect other than along the vertices and edge
//! they share (by vertex id). Exact: every decision is a CGAL predicate.
bool faces_intersect(const Mesh& mesh, std::size_t f, std::size_t g) {
  const Triangle& s = mesh.faces[f];
  const Triangle& t = mesh.faces[g];
  int shared_s[3], shared_t[3];
  int num_shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (s[static_cast<std::size_t>(i)] == t[static_cast<std::size_t>(j)]) {
        shared_s[num_shared] = i;
        shared_t[num_shared] = j;
        ++num_shared;
      }
  const auto corner = [&](const Triangle& tri, int i) { return point(mesh, tri[static_cast<std::size_t>(i % 3)]); };
  if (num_shared == 3) return true;  // the same triangle twice
  if (num_shared == 2) {
    // Shared edge u-v: they overlap only if the two opposite corners are
    // coplanar with it and on the same side of it.
    const int opposite_s = 3 - shared_s[0] - shared_s[1];
    const int opposite_t = 3 - shared_t[0] - shared_t[1];
    const Point u = corner(s, shared_s[0]);
    const Point v = corner(s, shared_s[1]);
    const Point p = corner(s, opposite_s);
    const Point q = corner(t, opposite_t);
    return CGAL::coplanar(u, v, p, q) && CGAL::coplanar_orientation(u, v, p, q) == CGAL::POSITIVE;
  }
  if (num_shared == 1) {
    // Quick exact rejection: if the other two corners of one face lie
    // strictly on one side of the other face's plane, the faces meet only
    // at the shared vertex.
    const auto one_side = [&](const Triangle& a, const Triangle& b, int shared_b) {
      const CGAL::Orientation o1 =
          CGAL::orientation(corner(a, 0), corner(a, 1), corner(a, 2), corner(b, shared_b + 1));
      const CGAL::Orientation o2 =
          CGAL::orientation(corner(a, 0), corner(a, 1), corner(a, 2), corner(b, shared_b + 2));
      return o1 == o2 && o1 != CGAL::COPLANAR;
    };
    if (one_side(s, t, shared_t[0]) || one_side(t, s, shared_s[0])) return false;
  }
  const Triangle3 ts(corner(s, 0), corner(s, 1), corner(s, 2));
  const Triangle3 tt(corner(t, 0), corner(t, 1), corner(t, 2));
  if (num_shared == 1) {
    // Shared vertex: the intersection is more than that vertex iff the edge
    // opposite it in one face meets the other face.
    const Segment opposite_s(corner(s, shared_s[0] + 1), corner(s, shared_s[0] + 2));
    const Segment opposite_t(corner(t, shared_t[0] + 1), corner(t, shared_t[0] + 2));
    return CGAL::do_intersect(ts, opposite_t) || CGAL::do_intersect(tt, opposite_s);
  }
  return CGAL::do_intersect(ts, tt);
}

//! True when face f is tested at all: no repeated index, corners not collinear
//! (degenerate faces are check_degenerate_faces()'s).
bool is_tested(const Mesh& mesh, std::size_t f) {
  const Triangle& t = mesh.faces[f];
  return !has_repeated_index(t) && !CGAL::collinear(point(mesh, t[0]), point(mesh, t[1]), point(mesh, t[2]));
}

CGAL::Bbox_3 face_bbox(const Mesh& mesh, std::size_t f) {
  const Triangle& t = mesh.faces[f];
  return point(mesh, t[0]).bbox() + point(mesh, t[1]).bbox() + point(mesh, t[2]).bbox();
}

}  // namespace

std::size_t count_self_intersections_of(const Mesh& mesh, const std::vector<int>& faces) {
  require_valid_indices(mesh, "self_intersections");
  require_finite_coordinates(mesh, "self_intersections");
  std::vector<std::size_t> own;  // the tested faces among `faces`
  std::vector<CGAL::Bbox_3> own_box;
  std::vector<char> in_set(mesh.num_faces(), 0);
  for (const int f : faces) {
    if (f < 0 || static_cast<std::size_t>(f) >= mesh.num_faces())
      throw InvalidArgumentError("count_self_intersections_of: face id " + std::to_string(f) + " out of range");
    const auto fs = static_cast<std::size_t>(f);
    in_set[fs] = 1;
    if (!is_tested(mesh, fs)) continue;
    own.push_back(fs);
    own_box.push_back(face_bbox(mesh, fs));
  }
  std::size_t count = 0;
  for (std::size_t g = 0; g < mesh.num_faces(); ++g) {
    const CGAL::Bbox_3 gb = face_bbox(mesh, g);
    bool tested = false, known = false;
    for (std::size_t i = 0; i < own.size(); ++i) {
      const std::size_t f = own[i];
      if (g == f || (in_set[g] && g < f)) continue;  // each pair once (and f, g both in the set: from the smaller)
      if (!CGAL::do_overlap(gb, own_box[i])) continue;
      if (!known) {
        tested = is_tested(mesh, g);
        known = true;
      }
      if (tested && faces_intersect(mesh, std::min(f, g), std::max(f, g))) ++count;
    }
  }
  return count;
}

CheckResult check_self_intersections(const Mesh& mesh, const CheckOptions& options) {
  require_valid_indices(mesh, "self_intersections");
  require_finite_coordinates(mesh, "self_intersections");

  std::vector<Box> boxes;
  boxes.reserve(mesh.num_faces());
  for (std::size_t f = 0; f < mesh.num_faces(); ++f)
    if (is_tested(mesh, f)) boxes.emplace_back(face_bbox(mesh, f), &mesh.faces[f]);

  std::vector<FacePair> intersecting;
  std::vector<FacePair> batch;
  const auto test_batch = [&] {
    std::vector<char> hit(batch.size(), 0);
    parallel_for(
        0, batch.size(),
        [&](std::size_t i) { hit[i] = faces_intersect(mesh, batch[i].first, batch[i].second); },
        1024);
    for (std::size_t i = 0; i < batch.size(); ++i)
      if (hit[i]) intersecting.push_back(batch[i]);
    batch.clear();
  };
  const Triangle* base = mesh.faces.data();
  // Sorting pointers is cheaper than sorting the boxes themselves.
  std::vector<const Box*> box_pointers;
  box_pointers.reserve(boxes.size());
  for (const Box& box : boxes) box_pointers.push_back(&box);
  CGAL::box_self_intersection_d(
      box_pointers.begin(), box_pointers.end(),
      [&](const Box* x, const Box* y) {
        auto f = static_cast<std::uint32_t>(x->handle() - base);
        auto g = static_cast<std::uint32_t>(y->handle() - base);
        if (f > g) std::swap(f, g);
        batch.emplace_back(f, g);
        if (batch.size() >= kBatch) test_batch();
      },
      CGAL::Box_intersection_d::Box_traits_d<const Box*>(), kBoxCutoff);
  test_batch();

  std::sort(intersecting.begin(), intersecting.end());
  intersecting.erase(std::unique(intersecting.begin(), intersecting.end()), intersecting.end());
  if (intersecting.empty())
    return passed_result("self_intersections", CheckElement::Face,
                         "the surface does not intersect itself");
  std::vector<int> faces;
  for (const auto& [f, g] : intersecting) {
    if (faces.size() >= options.max_examples) break;
    for (const std::uint32_t x : {f, g})
      if (faces.size() < options.max_examples &&
          std::find(faces.begin(), faces.end(), static_cast<int>(x)) == faces.end())
        faces.push_back(static_cast<int>(x));
  }
  std::sort(faces.begin(), faces.end());
  std::ostringstream message;
  message << "the surface intersects itself: "
          << count_of(intersecting.size(), "pair", "pairs") << " of faces intersect, e.g. faces "
          << intersecting.front().first << " and " << intersecting.front().second
          << "; remove the self-intersections (e.g. remesh, or a boolean union of the "
             "overlapping parts)";
  return failed_result("self_intersections", CheckElement::Face, intersecting.size(), faces,
                       message.str());
}

}  // namespace subfab
