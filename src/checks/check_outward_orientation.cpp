// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/check_outward_orientation.h"

#include <CGAL/Exact_rational.h>

#include <cmath>
#include <limits>
#include <sstream>

#include "checks/edge_topology.h"

namespace subfab {

using namespace checks_detail;

namespace {

//! Sign of sum over faces of det(a - o, b - o, c - o) (six times the signed
//! volume), decided exactly. First a floating-point sum with a forward error
//! bound; if the bound does not decide the sign, an exact rational sum.
int signed_volume_sign(const Mesh& mesh, const Vec3& o) {
  double sum = 0;
  double magnitude = 0;  // sum of the permanents |a||b||c| of the determinants
  for (const auto& t : mesh.faces) {
    const Vec3 a = mesh.vertices[static_cast<std::size_t>(t[0])] - o;
    const Vec3 b = mesh.vertices[static_cast<std::size_t>(t[1])] - o;
    const Vec3 c = mesh.vertices[static_cast<std::size_t>(t[2])] - o;
    sum += a.dot(b.cross(c));
    const Vec3 aa = a.cwiseAbs(), ba = b.cwiseAbs(), ca = c.cwiseAbs();
    magnitude += aa.dot(Vec3(ba.y() * ca.z() + ba.z() * ca.y(), ba.z() * ca.x() + ba.x() * ca.z(),
                             ba.x() * ca.y() + ba.y() * ca.x()));
  }
  // Rounding of the differences (3u per product), of the determinant (< 8u)
  // and of the running sum ((#F - 1) u of the magnitude); doubled for margin.
  const double u = std::numeric_limits<double>::epsilon() / 2;
  const double bound = 2.0 * (static_cast<double>(mesh.num_faces()) + 16.0) * u * magnitude;
  if (std::isfinite(sum) && std::abs(sum) > bound) return sum > 0 ? 1 : -1;

  using Q = CGAL::Exact_rational;
  Q exact = 0;
  const Q ox = o.x(), oy = o.y(), oz = o.z();
  for (const auto& t : mesh.faces) {
    Q p[3][3];
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3& v = mesh.vertices[static_cast<std::size_t>(t[k])];
      p[k][0] = Q(v.x()) - ox;
      p[k][1] = Q(v.y()) - oy;
      p[k][2] = Q(v.z()) - oz;
    }
    exact += p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) -
             p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
             p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
  }
  return CGAL::sign(exact);
}

}  // namespace

CheckResult check_outward_orientation(const Mesh& mesh, const CheckOptions& options) {
  require_valid_indices(mesh, "outward_orientation");
  require_finite_coordinates(mesh, "outward_orientation");
  const BoundingBox box = bounding_box(mesh);
  const Vec3 centre = box.is_empty() ? Vec3::Zero() : Vec3(0.5 * (box.min + box.max));
  const int sign = signed_volume_sign(mesh, centre);
  if (sign > 0)
    return passed_result("outward_orientation", CheckElement::Face,
                         "the faces point outward (positive volume)");
  CheckResult result;
  result.name = "outward_orientation";
  result.status = CheckStatus::Failed;
  result.element = CheckElement::Face;
  std::ostringstream message;
  if (sign < 0) {
    result.num_offending = mesh.num_faces();
    message << "the mesh is oriented inward: its signed volume is negative ("
            << signed_volume(mesh)
            << "), so all faces point into the solid; flip all faces (subfab does it for you)";
  } else {
    message << "the mesh encloses no volume (signed volume exactly 0); it is flat or its parts "
               "cancel out: check that the mesh is a solid";
  }
  result.message = message.str();
  return result;
}

}  // namespace subfab
