// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/mill/drop_cutter.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "subfab/core/error.h"

namespace subfab {
namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

//! True when (x, y) lies in the xy projection of the triangle (boundary
//! included, with a relative tolerance of 1e-12 of the doubled area).
bool inside_xy(const TriangleGrid::Tri& t, double x, double y) {
  const double d1 = (t.b.x() - t.a.x()) * (y - t.a.y()) - (t.b.y() - t.a.y()) * (x - t.a.x());
  const double d2 = (t.c.x() - t.b.x()) * (y - t.b.y()) - (t.c.y() - t.b.y()) * (x - t.b.x());
  const double d3 = (t.a.x() - t.c.x()) * (y - t.c.y()) - (t.a.y() - t.c.y()) * (x - t.c.x());
  const double area = (t.b.x() - t.a.x()) * (t.c.y() - t.a.y()) - (t.b.y() - t.a.y()) * (t.c.x() - t.a.x());
  const double eps = -1e-12 * std::abs(area);
  return (d1 >= eps && d2 >= eps && d3 >= eps) || (d1 <= -eps && d2 <= -eps && d3 <= -eps);
}

//! Height of the plane of t above (x, y) (t not vertical).
double plane_z(const TriangleGrid::Tri& t, double x, double y) {
  const Vec3& n = t.normal;  // either orientation: the ratio below does not depend on it
  return t.a.z() - (n.x() * (x - t.a.x()) + n.y() * (y - t.a.y())) / n.z();
}

//! Ball of radius r: contact height (tip) on edge a-b, or -inf.
double ball_edge(const Vec3& a, const Vec3& b, double x, double y, double r) {
  const double ux = b.x() - a.x(), uy = b.y() - a.y();
  const double l2 = ux * ux + uy * uy;
  if (l2 <= 1e-24) return kNegInf;  // vertical edge: its top vertex is the contact
  const double len = std::sqrt(l2);
  const double px = x - a.x(), py = y - a.y();
  const double s_p = (px * ux + py * uy) / len;  // along the edge, horizontally
  const double perp2 = std::max(0.0, px * px + py * py - s_p * s_p);
  if (perp2 > r * r) return kNegInf;
  const double rr = std::sqrt(r * r - perp2);  // radius of the sphere's section by the edge's vertical plane
  const double m = (b.z() - a.z()) / len;      // slope of the edge
  const double k = std::sqrt(1.0 + m * m);
  const double s_c = s_p + rr * m / k;  // tangent point
  if (s_c < 0.0 || s_c > len) return kNegInf;
  const double centre = a.z() + m * s_p + rr * k;
  return centre - r;
}

//! Flat end of radius r: contact height on edge a-b (rim crossings), or -inf.
double flat_edge(const Vec3& a, const Vec3& b, double x, double y, double r) {
  const double ux = b.x() - a.x(), uy = b.y() - a.y();
  const double l2 = ux * ux + uy * uy;
  if (l2 <= 1e-24) return kNegInf;
  const double px = a.x() - x, py = a.y() - y;
  const double half_b = px * ux + py * uy;
  const double c = px * px + py * py - r * r;
  const double disc = half_b * half_b - l2 * c;
  if (disc < 0.0) return kNegInf;
  const double sq = std::sqrt(disc);
  double best = kNegInf;
  for (double t : {(-half_b - sq) / l2, (-half_b + sq) / l2})
    if (t >= 0.0 && t <= 1.0) best = std::max(best, a.z() + t * (b.z() - a.z()));
  return best;
}

double contact(const TriangleGrid::Tri& t, const Tool& tool, double x, double y) {
  const double r = tool.radius(), r2 = r * r;
  const bool ball = tool.shape == ToolShape::Ball;
  double best = kNegInf;
  for (const Vec3* v : {&t.a, &t.b, &t.c}) {
    const double dx = v->x() - x, dy = v->y() - y, d2 = dx * dx + dy * dy;
    if (d2 <= r2) best = std::max(best, ball ? v->z() + std::sqrt(r2 - d2) - r : v->z());
  }
  const std::array<std::pair<const Vec3*, const Vec3*>, 3> edges = {{{&t.a, &t.b}, {&t.b, &t.c}, {&t.c, &t.a}}};
  for (const auto& [p, q] : edges)
    best = std::max(best, ball ? ball_edge(*p, *q, x, y, r) : flat_edge(*p, *q, x, y, r));
  // Facet: the side facing up (a triangle soup's orientation does not matter).
  const Vec3 n = t.normal.z() < 0.0 ? Vec3(-t.normal) : t.normal;
  if (n.z() > 1e-12) {
    const double nxy = std::hypot(n.x(), n.y());
    double qx = x, qy = y;  // contact point's xy
    if (ball) {
      qx -= r * n.x();
      qy -= r * n.y();
    } else if (nxy > 1e-15) {
      qx -= r * n.x() / nxy;
      qy -= r * n.y() / nxy;
    }
    if (inside_xy(t, qx, qy)) {
      // Ball: the centre is the tangent point plus r times the normal; flat: the rim point on the plane.
      best = std::max(best, ball ? plane_z(t, qx, qy) + r * n.z() - r : plane_z(t, qx, qy));
    }
  }
  return best;
}

}  // namespace

TriangleGrid::TriangleGrid(const Mesh& mesh, double cell_size) {
  if (!(cell_size > 0.0)) throw InvalidArgumentError("TriangleGrid: cell size must be positive");
  BoundingBox box;
  tris_.reserve(mesh.num_faces());
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const Triangle& tri = mesh.faces[f];
    Tri t{mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]], face_unit_normal(mesh, f), 0.0};
    t.top = std::max({t.a.z(), t.b.z(), t.c.z()});
    for (const Vec3* v : {&t.a, &t.b, &t.c}) box.extend(*v);
    tris_.push_back(t);
  }
  if (tris_.empty()) return;
  cell_ = cell_size;
  x0_ = box.min.x();
  y0_ = box.min.y();
  nx_ = std::max(1, static_cast<int>(std::ceil((box.max.x() - x0_) / cell_)) + 1);
  ny_ = std::max(1, static_cast<int>(std::ceil((box.max.y() - y0_) / cell_)) + 1);
  cells_.assign(static_cast<std::size_t>(nx_) * ny_, {});
  for (std::size_t f = 0; f < tris_.size(); ++f) {
    const Tri& t = tris_[f];
    const double lx = std::min({t.a.x(), t.b.x(), t.c.x()}), hx = std::max({t.a.x(), t.b.x(), t.c.x()});
    const double ly = std::min({t.a.y(), t.b.y(), t.c.y()}), hy = std::max({t.a.y(), t.b.y(), t.c.y()});
    const int i0 = std::clamp(static_cast<int>(std::floor((lx - x0_) / cell_)), 0, nx_ - 1);
    const int i1 = std::clamp(static_cast<int>(std::floor((hx - x0_) / cell_)), 0, nx_ - 1);
    const int j0 = std::clamp(static_cast<int>(std::floor((ly - y0_) / cell_)), 0, ny_ - 1);
    const int j1 = std::clamp(static_cast<int>(std::floor((hy - y0_) / cell_)), 0, ny_ - 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) cells_[static_cast<std::size_t>(j) * nx_ + i].push_back(static_cast<int>(f));
  }
}

void TriangleGrid::query(double x0, double y0, double x1, double y1, std::vector<int>& out) const {
  if (cells_.empty()) return;
  const int i0 = static_cast<int>(std::floor((x0 - x0_) / cell_)), i1 = static_cast<int>(std::floor((x1 - x0_) / cell_));
  const int j0 = static_cast<int>(std::floor((y0 - y0_) / cell_)), j1 = static_cast<int>(std::floor((y1 - y0_) / cell_));
  if (i1 < 0 || j1 < 0 || i0 >= nx_ || j0 >= ny_) return;
  // Each triangle once: a per-thread mark per triangle id, stamped with a
  // query counter that only grows (so marks left by another grid are stale).
  thread_local std::vector<std::uint64_t> mark;
  thread_local std::uint64_t stamp = 0;
  if (mark.size() < tris_.size()) mark.resize(tris_.size(), 0);
  ++stamp;
  for (int j = std::max(j0, 0); j <= std::min(j1, ny_ - 1); ++j)
    for (int i = std::max(i0, 0); i <= std::min(i1, nx_ - 1); ++i)
      for (int id : cells_[static_cast<std::size_t>(j) * nx_ + i]) {
        std::uint64_t& m = mark[static_cast<std::size_t>(id)];
        if (m == stamp) continue;
        m = stamp;
        out.push_back(id);
      }
}

double drop_cutter(const TriangleGrid& grid, const Tool& tool, double x, double y, double floor) {
  thread_local std::vector<int> ids;
  ids.clear();
  const double r = tool.radius();
  grid.query(x - r, y - r, x + r, y + r, ids);
  double best = floor;
  for (int id : ids) {
    const TriangleGrid::Tri& t = grid.triangles()[static_cast<std::size_t>(id)];
    if (t.top <= best) continue;  // every contact lies at or below the triangle's highest corner
    best = std::max(best, contact(t, tool, x, y));
  }
  return best;
}

}  // namespace subfab
