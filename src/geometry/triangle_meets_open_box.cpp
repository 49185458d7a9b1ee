// SPDX-License-Identifier: GPL-3.0-or-later
// Exact triangle / open-box contact test (separating axes, exact signs),
// see triangle_meets_open_box.h.
#include "geometry/triangle_meets_open_box.h"

#include <algorithm>
#include <array>

#include "geometry/exact_determinant_signs.h"

namespace subfab::detail {

bool triangle_meets_open_box(const Vec3& a, const Vec3& b, const Vec3& c, const Box3& box) {
  const Vec3& lo = box.min;
  const Vec3& hi = box.max;
  for (int k = 0; k < 3; ++k)
    if (!(hi[k] > lo[k])) return false;  // empty interior
  // 1. Box face normals: the triangle's bounding box. When it lies in the
  //    open box, so does the triangle (convex): it meets it.
  bool inside = true;
  for (int k = 0; k < 3; ++k) {
    const double tmin = std::min({a[k], b[k], c[k]});
    const double tmax = std::max({a[k], b[k], c[k]});
    if (tmax <= lo[k] || tmin >= hi[k]) return false;
    inside = inside && tmin > lo[k] && tmax < hi[k];
  }
  if (inside) return true;
  // 2. Triangle normal n: separated iff the whole box is weakly on one side
  //    of the triangle's plane (skipped when n = 0).
  {
    std::array<int, 3> s{};
    for (int k = 0; k < 3; ++k) s[k] = normal_component_sign(a, b, c, k);
    if (s[0] != 0 || s[1] != 0 || s[2] != 0) {
      Vec3 rmin, rmax;  // box corners minimising / maximising n.x
      for (int k = 0; k < 3; ++k) {
        rmin[k] = s[k] > 0 ? lo[k] : hi[k];
        rmax[k] = s[k] > 0 ? hi[k] : lo[k];
      }
      if (orient3d_sign(a, b, c, rmin) >= 0) return false;
      if (orient3d_sign(a, b, c, rmax) <= 0) return false;
    }
  }
  // 3. Cross products e_k x (q - p) for every box axis k and triangle edge
  //    (p, q), r the third vertex. In the plane (i, j) orthogonal to k the
  //    functional is f(x) = e_i x_j - e_j x_i with e = q - p.
  const std::array<const Vec3*, 3> v = {&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3;
    const int j = (k + 2) % 3;
    for (int e = 0; e < 3; ++e) {
      const Vec3& p = *v[e];
      const Vec3& q = *v[(e + 1) % 3];
      const Vec3& r = *v[(e + 2) % 3];
      const int si = sign_of_number(q[i] - p[i]);  // exact: sign of a difference of doubles
      const int sj = sign_of_number(q[j] - p[j]);
      if (si == 0 && sj == 0) continue;  // edge parallel to e_k: zero axis
      // Corner of the box rectangle minimising f (coefficient of x_j is e_i,
      // of x_i is -e_j), and the one maximising it.
      const double min_j = si > 0 ? lo[j] : hi[j];
      const double min_i = sj > 0 ? hi[i] : lo[i];
      const double max_j = si > 0 ? hi[j] : lo[j];
      const double max_i = sj > 0 ? lo[i] : hi[i];
      // sign of f(corner) - f(x) = e_i (corner_j - x_j) - e_j (corner_i - x_i)
      auto diff_sign = [&](double ci, double cj, const Vec3& x) {
        return det2_sign(q[i], p[i], q[j], p[j], ci, x[i], cj, x[j]);
      };
      // Triangle entirely below the box's minimum: f(rmin) >= f(p) = f(q), f(r).
      if (diff_sign(min_i, min_j, p) >= 0 && diff_sign(min_i, min_j, r) >= 0) return false;
      // Triangle entirely above the box's maximum.
      if (diff_sign(max_i, max_j, p) <= 0 && diff_sign(max_i, max_j, r) <= 0) return false;
    }
  }
  return true;
}

}  // namespace subfab::detail
