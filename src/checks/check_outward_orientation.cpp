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

//! Sign of sum over `faces` of det(a - o, b - o, c - o) (six times the signed
//! volume, about o = the centre of the faces' bounding box), decided
//! exactly: a floating-point sum with a forward error bound, and an exact
//! rational sum when the bound does not decide.
int signed_volume_sign(const Mesh& mesh, const std::vector<int>& faces) {
  BoundingBox box;
  for (int f : faces)
    for (int v : mesh.faces[static_cast<std::size_t>(f)])
      box.extend(mesh.vertices[static_cast<std::size_t>(v)]);
  const Vec3 o = box.is_empty() ? Vec3::Zero() : Vec3(0.5 * (box.min + box.max));
  double sum = 0;
  double magnitude = 0;  // sum of the permanents |a||b||c| of the determinants
  for (int f : faces) {
    const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
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
  const double bound = 2.0 * (static_cast<double>(faces.size()) + 16.0) * u * magnitude;
  if (std::isfinite(sum) && std::abs(sum) > bound) return sum > 0 ? 1 : -1;

  using Q = CGAL::Exact_rational;
  Q exact = 0;
  const Q ox = o.x(), oy = o.y(), oz = o.z();
  for (int f : faces) {
    const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
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

bool box_inside(const BoundingBox& inner, const BoundingBox& outer) {
  return (outer.min.array() <= inner.min.array()).all() &&
         (inner.max.array() <= outer.max.array()).all();
}

}  // namespace

CheckResult check_outward_orientation(const Mesh& mesh, const CheckOptions& options) {
  require_valid_indices(mesh, "outward_orientation");
  require_finite_coordinates(mesh, "outward_orientation");
  CheckResult result;
  result.name = "outward_orientation";
  result.status = CheckStatus::Failed;
  result.element = CheckElement::Face;
  std::ostringstream message;

  std::vector<int> all_faces(mesh.num_faces());
  for (std::size_t f = 0; f < all_faces.size(); ++f) all_faces[f] = static_cast<int>(f);
  const int sign = signed_volume_sign(mesh, all_faces);
  if (sign < 0) {
    result.num_offending = mesh.num_faces();
    message << "the mesh is oriented inward: its signed volume is negative ("
            << signed_volume(mesh)
            << "), so all faces point into the solid; flip all faces (subfab does it for you)";
    result.message = message.str();
    return result;
  }
  if (sign == 0) {
    message << "the mesh encloses no volume (signed volume exactly 0); it is flat or its parts "
               "cancel out: check that the mesh is a solid";
    result.message = message.str();
    return result;
  }

  // Positive in total; an inward component is fine only as a cavity, which
  // requires its bounding box to lie inside that of an outward component.
  const FaceComponents components = label_face_components(mesh);
  if (components.num_components > 1) {
    std::vector<std::vector<int>> faces_of(components.num_components);
    for (std::size_t f = 0; f < mesh.num_faces(); ++f)
      faces_of[static_cast<std::size_t>(components.face_component[f])].push_back(
          static_cast<int>(f));
    std::vector<int> signs(components.num_components);
    std::vector<BoundingBox> boxes(components.num_components);
    for (std::size_t c = 0; c < components.num_components; ++c) {
      signs[c] = signed_volume_sign(mesh, faces_of[c]);
      for (int f : faces_of[c])
        for (int v : mesh.faces[static_cast<std::size_t>(f)])
          boxes[c].extend(mesh.vertices[static_cast<std::size_t>(v)]);
    }
    std::vector<int> inside_out;  // first face of each inward component enclosed by nothing
    std::size_t num_faces = 0;
    for (std::size_t c = 0; c < components.num_components; ++c) {
      if (signs[c] >= 0) continue;
      bool enclosed = false;
      for (std::size_t d = 0; d < components.num_components && !enclosed; ++d)
        enclosed = d != c && signs[d] > 0 && box_inside(boxes[c], boxes[d]);
      if (enclosed) continue;
      inside_out.push_back(faces_of[c].front());
      num_faces += faces_of[c].size();
    }
    if (!inside_out.empty()) {
      result.num_offending = num_faces;
      result.examples = first_ids(inside_out, options.max_examples);
      message << count_of(inside_out.size(), "component is", "components are")
              << " oriented inward but not inside another part (so not a cavity), e.g. the one "
                 "with face "
              << inside_out.front() << "; flip the faces of "
              << (inside_out.size() == 1 ? "that component" : "those components");
      result.message = message.str();
      return result;
    }
  }
  return passed_result("outward_orientation", CheckElement::Face,
                       "the faces point outward (positive volume)");
}

}  // namespace subfab
