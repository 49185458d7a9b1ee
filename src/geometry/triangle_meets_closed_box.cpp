// SPDX-License-Identifier: GPL-3.0-or-later
#include "triangle_meets_closed_box.h"

#include <algorithm>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

namespace subfab::detail {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
Kernel::Point_3 point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
}  // namespace

bool triangle_meets_closed_box(const Vec3& a, const Vec3& b, const Vec3& c, const Box3& box) {
  // Epick's Do_intersect_3 predicates are filtered and exact.
  const Kernel::Iso_cuboid_3 cuboid(point(box.min), point(box.max));
  const Kernel::Point_3 pa = point(a), pb = point(b), pc = point(c);
  if (!CGAL::collinear(pa, pb, pc)) return CGAL::do_intersect(Kernel::Triangle_3(pa, pb, pc), cuboid);
  // Degenerate: the segment between the two extreme points (or a point).
  const Kernel::Point_3 lo = std::min({pa, pb, pc});
  const Kernel::Point_3 hi = std::max({pa, pb, pc});
  if (lo == hi) return CGAL::do_intersect(lo, cuboid);
  return CGAL::do_intersect(Kernel::Segment_3(lo, hi), cuboid);
}

}  // namespace subfab::detail
