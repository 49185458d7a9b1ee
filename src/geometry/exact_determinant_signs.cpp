// SPDX-License-Identifier: GPL-3.0-or-later
// Exact signs of small determinants with a floating-point filter, see
// exact_determinant_signs.h.
#include "geometry/exact_determinant_signs.h"

#include <CGAL/Exact_rational.h>

#include <cmath>

namespace subfab::detail {
namespace {

using Exact = CGAL::Exact_rational;

constexpr double kEps = 0x1p-53;  // half an ulp of 1 (Shewchuk's epsilon)
// Error bounds of Shewchuk's orient2d / orient3d, which have exactly the
// structure evaluated below (products of rounded differences of inputs).
constexpr double kDet2Bound = (3.0 + 16.0 * kEps) * kEps;
constexpr double kDet3Bound = (7.0 + 56.0 * kEps) * kEps;
// Below this magnitude products may have underflowed: go exact.
constexpr double kTiny = 1e-280;

int sign_of(const Exact& x) { return CGAL::sign(x); }

}  // namespace

int det2_sign(double ux1, double ux0, double uy1, double uy0, double vx1, double vx0, double vy1,
              double vy0) {
  const double t1 = (ux1 - ux0) * (vy1 - vy0);
  const double t2 = (uy1 - uy0) * (vx1 - vx0);
  const double det = t1 - t2;
  const double sum = std::abs(t1) + std::abs(t2);
  if (sum > kTiny && std::isfinite(sum) && std::abs(det) > kDet2Bound * sum) return sign_of_number(det);
  if (sum == 0.0 && t1 == 0.0 && t2 == 0.0) {
    // Both products are exactly zero iff one factor of each is exactly zero
    // (products of nonzero doubles can only underflow below kTiny: handled
    // by the exact path, since then sum <= kTiny but some factor is nonzero).
    const bool z1 = (ux1 == ux0) || (vy1 == vy0);
    const bool z2 = (uy1 == uy0) || (vx1 == vx0);
    if (z1 && z2) return 0;
  }
  const Exact e = (Exact(ux1) - Exact(ux0)) * (Exact(vy1) - Exact(vy0)) -
                  (Exact(uy1) - Exact(uy0)) * (Exact(vx1) - Exact(vx0));
  return sign_of(e);
}

int normal_component_sign(const Vec3& a, const Vec3& b, const Vec3& c, int dim) {
  const int i = (dim + 1) % 3;
  const int j = (dim + 2) % 3;
  // n_dim = (b - a)_i (c - a)_j - (b - a)_j (c - a)_i
  return det2_sign(b[i], a[i], b[j], a[j], c[i], a[i], c[j], a[j]);
}

int orient3d_sign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  const double ux = b.x() - a.x(), uy = b.y() - a.y(), uz = b.z() - a.z();
  const double vx = c.x() - a.x(), vy = c.y() - a.y(), vz = c.z() - a.z();
  const double wx = p.x() - a.x(), wy = p.y() - a.y(), wz = p.z() - a.z();
  // det[u; v; w] = w . (u x v)
  const double m1a = uy * vz, m1b = uz * vy;
  const double m2a = uz * vx, m2b = ux * vz;
  const double m3a = ux * vy, m3b = uy * vx;
  const double det = wx * (m1a - m1b) + wy * (m2a - m2b) + wz * (m3a - m3b);
  const double permanent = std::abs(wx) * (std::abs(m1a) + std::abs(m1b)) +
                           std::abs(wy) * (std::abs(m2a) + std::abs(m2b)) +
                           std::abs(wz) * (std::abs(m3a) + std::abs(m3b));
  if (permanent > kTiny && std::isfinite(permanent) && std::abs(det) > kDet3Bound * permanent)
    return sign_of_number(det);
  const Exact eux = Exact(b.x()) - Exact(a.x()), euy = Exact(b.y()) - Exact(a.y()),
              euz = Exact(b.z()) - Exact(a.z());
  const Exact evx = Exact(c.x()) - Exact(a.x()), evy = Exact(c.y()) - Exact(a.y()),
              evz = Exact(c.z()) - Exact(a.z());
  const Exact ewx = Exact(p.x()) - Exact(a.x()), ewy = Exact(p.y()) - Exact(a.y()),
              ewz = Exact(p.z()) - Exact(a.z());
  const Exact e = ewx * (euy * evz - euz * evy) + ewy * (euz * evx - eux * evz) + ewz * (eux * evy - euy * evx);
  return sign_of(e);
}

}  // namespace subfab::detail
