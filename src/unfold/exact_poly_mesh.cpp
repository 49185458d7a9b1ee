// SPDX-License-Identifier: GPL-3.0-or-later
//! \file exact_poly_mesh.cpp
//! The exact polygonal mesh of facet deletion (thesis Section 3.3.2):
//! conversion from and to a PolyMesh on the 1/24 sub-lattice, exact vector
//! arithmetic, loop and facet areas. The checks and clean-ups on it are in
//! check_closed_manifold.cpp, check_no_intersections.cpp and
//! merge_coplanar_neighbours.cpp.
#include "unfold/exact_poly_mesh.h"

#include <cmath>

#include "subfab/core/error.h"
#include "subfab/unfold/lattice_directions.h"

namespace subfab::unfold_detail {

QVec operator+(const QVec& a, const QVec& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
QVec operator-(const QVec& a, const QVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
QVec operator*(const Q& s, const QVec& a) { return {s * a.x, s * a.y, s * a.z}; }
bool operator==(const QVec& a, const QVec& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
Q dot(const QVec& a, const QVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
QVec cross(const QVec& a, const QVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
QVec to_qvec(const std::array<int, 3>& v) { return {Q(v[0]), Q(v[1]), Q(v[2])}; }
bool is_zero(const QVec& a) { return CGAL::is_zero(a.x) && CGAL::is_zero(a.y) && CGAL::is_zero(a.z); }

namespace {

constexpr int kDenominator = 24;

}  // namespace

Vec3 to_model(const QVec& q, const LatticeFrame& frame) {
  const Vec3 v(CGAL::to_double(q.x), CGAL::to_double(q.y), CGAL::to_double(q.z));
  if (frame.step > 0) return frame.origin + frame.step * v;
  return v;
}

int add_point(ExactPolyMesh& mesh, const QVec& q) {
  mesh.points.push_back(q);
  mesh.approx.push_back(to_model(q, mesh.frame));
  return static_cast<int>(mesh.points.size()) - 1;
}

ExactPolyMesh to_exact(const PolyMesh& mesh, const LatticeFrame& frame) {
  ExactPolyMesh out;
  out.frame = frame;
  out.points.reserve(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& x = mesh.vertices[i];
    QVec q;
    if (frame.step > 0) {
      for (int k = 0; k < 3; ++k) {
        const double m = std::round((x[k] - frame.origin[k]) / frame.step * kDenominator);
        const double back = frame.origin[k] + frame.step * (m / kDenominator);
        if (!(std::abs(back - x[k]) <= 1e-6 * frame.step))
          throw InvalidArgumentError("vertex " + std::to_string(i) +
                                     " is not on the lattice of the polygonal mesh (grid step " +
                                     std::to_string(frame.step) + ")");
        q[k] = Q(m) / Q(kDenominator);
      }
    } else {
      q = {Q(x[0]), Q(x[1]), Q(x[2])};
    }
    out.points.push_back(q);
    out.approx.push_back(x);
  }
  const auto& dirs = lattice_directions();
  for (std::size_t f = 0; f < mesh.facets.size(); ++f) {
    const Facet& in = mesh.facets[f];
    if (in.loops.empty() || in.loops[0].size() < 3)
      throw InvalidArgumentError("facet " + std::to_string(f) + " has no outer loop");
    QFacet qf;
    qf.loops = in.loops;
    int normal = in.normal;
    if (normal < 0) {
      Vec3 nsum = Vec3::Zero();
      const auto& loop = in.loops[0];
      for (std::size_t i = 0; i < loop.size(); ++i)
        nsum += mesh.vertices[loop[i]].cross(mesh.vertices[loop[(i + 1) % loop.size()]]);
      const auto idx = lattice_direction_index(nsum, 1e-6);
      if (!idx)
        throw InvalidArgumentError("facet " + std::to_string(f) +
                                   " has a normal that is not one of the 26 lattice directions");
      normal = *idx;
    }
    if (normal >= 26) throw InvalidArgumentError("facet " + std::to_string(f) + ": normal index out of range");
    qf.normal_index = normal;
    qf.normal = dirs[normal];
    const QVec n = to_qvec(qf.normal);
    qf.offset = dot(n, out.points[in.loops[0][0]]);
    for (const auto& loop : in.loops)
      for (int v : loop) {
        if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertices.size())
          throw InvalidArgumentError("facet " + std::to_string(f) + " refers to a missing vertex");
        if (dot(n, out.points[v]) != qf.offset)
          throw InvalidArgumentError("facet " + std::to_string(f) + " is not planar (vertex " +
                                     std::to_string(v) + " is off its plane)");
      }
    out.facets.push_back(std::move(qf));
  }
  return out;
}

PolyMesh to_poly_mesh(const ExactPolyMesh& mesh) {
  PolyMesh out;
  std::vector<int> remap(mesh.points.size(), -1);
  for (const auto& f : mesh.facets) {
    if (!f.alive) continue;
    Facet g;
    g.normal = f.normal_index;
    for (const auto& loop : f.loops) {
      std::vector<int> l;
      for (int v : loop) {
        if (remap[v] < 0) {
          remap[v] = static_cast<int>(out.vertices.size());
          out.vertices.push_back(to_model(mesh.points[v], mesh.frame));
        }
        l.push_back(remap[v]);
      }
      g.loops.push_back(std::move(l));
    }
    out.facets.push_back(std::move(g));
  }
  return out;
}

Q loop_area2(const ExactPolyMesh& mesh, const QFacet& facet, const std::vector<int>& loop) {
  const int k = drop_axis(facet);
  Q sum(0);
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const P2 a = project(mesh.points[loop[i]], k);
    const P2 b = project(mesh.points[loop[(i + 1) % n]], k);
    sum += a.u * b.v - a.v * b.u;
  }
  return facet.normal[k] > 0 ? sum : -sum;
}

double facet_area(const ExactPolyMesh& mesh, int f) {
  const QFacet& facet = mesh.facets[f];
  Q sum(0);
  for (const auto& loop : facet.loops) sum += loop_area2(mesh, facet, loop);
  // projected area * |n| / |n[k]| = true area (|n[k]| = 1); in lattice units
  const double n_len = std::sqrt(double(facet.normal[0] * facet.normal[0] + facet.normal[1] * facet.normal[1] +
                                        facet.normal[2] * facet.normal[2]));
  const double s = mesh.frame.step > 0 ? mesh.frame.step : 1.0;
  return 0.5 * CGAL::to_double(sum) * n_len * s * s;
}

}  // namespace subfab::unfold_detail
