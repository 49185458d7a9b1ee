// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/build_tubular_structure.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include "subfab/core/error.h"

namespace subfab {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

//! One end of an arc at a cube: which arc, which end, leaving direction.
struct ArcEnd {
  int arc = -1;
  bool at_front = true;
  Vec3 direction;
};

//! A face quad of a cube: outward, with the direction from the cube centre.
struct FaceQuad {
  Quad quad;
  Vec3 direction;
};

struct Cube {
  Vec3 centre;
  double half = 0;
  Eigen::Matrix3d frame;  // columns: the cube's axes
  int n = 1;
  std::vector<FaceQuad> faces;
};

struct Assignment {
  std::vector<int> face;  // per end, index into the cube's faces
  double worst = -2, sum = -1e300;
  bool better_than(const Assignment& o) const {
    return worst > o.worst + 1e-12 || (worst > o.worst - 1e-12 && sum > o.sum + 1e-12);
  }
};

//! Face quad directions of an n x n x n cube with the given frame (unit half-size).
std::vector<Vec3> face_directions(const Eigen::Matrix3d& frame, int n) {
  std::vector<Vec3> dirs;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          Vec3 local = Vec3::Zero();
          local[axis] = sign;
          local[(axis + 1) % 3] = -1 + (2.0 * a + 1) / n;
          local[(axis + 2) % 3] = -1 + (2.0 * b + 1) / n;
          dirs.push_back((frame * local).normalized());
        }
  return dirs;
}

Assignment assign(const std::vector<ArcEnd>& ends, const std::vector<Vec3>& dirs) {
  Assignment best;
  const std::size_t k = ends.size();
  if (k == 0) {
    best.worst = 1, best.sum = 0;
    return best;
  }
  if (k > dirs.size()) return best;
  if (dirs.size() <= 6) {  // exhaustive
    std::vector<int> current(k, -1);
    std::vector<bool> used(dirs.size(), false);
    auto search = [&](auto&& self, std::size_t e, double worst, double sum) -> void {
      if (e == k) {
        Assignment a{current, worst, sum};
        if (a.better_than(best)) best = a;
        return;
      }
      for (std::size_t f = 0; f < dirs.size(); ++f) {
        if (used[f]) continue;
        const double d = ends[e].direction.dot(dirs[f]);
        if (std::min(worst, d) < best.worst - 1e-12) continue;
        used[f] = true;
        current[e] = static_cast<int>(f);
        self(self, e + 1, std::min(worst, d), sum + d);
        used[f] = false;
      }
    };
    search(search, 0, 1.0, 0.0);
    return best;
  }
  std::vector<std::tuple<double, int, int>> pairs;  // greedy: best pairs first
  for (std::size_t e = 0; e < k; ++e)
    for (std::size_t f = 0; f < dirs.size(); ++f)
      pairs.emplace_back(-ends[e].direction.dot(dirs[f]), static_cast<int>(e), static_cast<int>(f));
  std::sort(pairs.begin(), pairs.end());
  best.face.assign(k, -1);
  std::vector<bool> used(dirs.size(), false);
  best.worst = 1, best.sum = 0;
  for (const auto& [neg, e, f] : pairs) {
    if (best.face[idx(e)] >= 0 || used[idx(f)]) continue;
    best.face[idx(e)] = f;
    used[idx(f)] = true;
    best.worst = std::min(best.worst, -neg);
    best.sum += -neg;
  }
  return best;
}

Vec3 any_perpendicular(const Vec3& d) {
  const Vec3 axis = std::abs(d.x()) <= std::abs(d.y()) && std::abs(d.x()) <= std::abs(d.z()) ? Vec3::UnitX()
                    : std::abs(d.y()) <= std::abs(d.z())                                       ? Vec3::UnitY()
                                                                                               : Vec3::UnitZ();
  return d.cross(axis).normalized();
}

//! Candidate frames from the arc directions.
std::vector<Eigen::Matrix3d> candidate_frames(const std::vector<ArcEnd>& ends) {
  std::vector<Eigen::Matrix3d> frames;
  auto add = [&](const Vec3& x, const Vec3& y) {
    Eigen::Matrix3d m;
    m.col(0) = x;
    m.col(1) = y;
    m.col(2) = x.cross(y);
    frames.push_back(m);
    const double c = std::sqrt(0.5);  // the same, turned 45 degrees about x
    m.col(1) = c * (y + x.cross(y));
    m.col(2) = x.cross(Vec3(m.col(1)));
    frames.push_back(m);
  };
  if (ends.empty()) {
    add(Vec3::UnitX(), Vec3::UnitY());
    return frames;
  }
  for (std::size_t i = 0; i < ends.size(); ++i) {
    const Vec3 x = ends[i].direction;
    bool any = false;
    for (std::size_t j = 0; j < ends.size(); ++j) {
      if (i == j) continue;
      const Vec3 y = ends[j].direction - ends[j].direction.dot(x) * x;
      if (y.norm() < 0.1) continue;
      add(x, y.normalized());
      any = true;
    }
    if (!any) add(x, any_perpendicular(x));
  }
  return frames;
}

//! Adds the hexahedra and vertices of an n x n x n cube; fills its face quads.
void add_cube(Cube& cube, int node, TubularStructure& out) {
  const int n = cube.n;
  const int base = static_cast<int>(out.mesh.vertices.size());
  auto vid = [&](int i, int j, int k) { return base + (k * (n + 1) + j) * (n + 1) + i; };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const Vec3 local(-1 + 2.0 * i / n, -1 + 2.0 * j / n, -1 + 2.0 * k / n);
        out.mesh.vertices.push_back(cube.centre + cube.half * (cube.frame * local));
        out.vertex_anchor.push_back(cube.centre);
      }
  std::vector<FaceQuad> faces;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Hex h{vid(i, j, k),         vid(i + 1, j, k),         vid(i + 1, j + 1, k),
                    vid(i, j + 1, k),     vid(i, j, k + 1),         vid(i + 1, j, k + 1),
                    vid(i + 1, j + 1, k + 1), vid(i, j + 1, k + 1)};
        out.mesh.hexes.push_back(h);
        out.hex_node.push_back(node);
        out.hex_arc.push_back(-1);
      }
  // face quads in the order of face_directions(): axis, sign, a, b
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          int c[3];
          c[axis] = sign < 0 ? 0 : n - 1;
          c[(axis + 1) % 3] = a;
          c[(axis + 2) % 3] = b;
          const std::size_t h = out.mesh.hexes.size() - idx(n * n * n) + idx((c[2] * n + c[1]) * n + c[0]);
          // local face of the hex on that side: bottom/top (z), front/back (y), left/right (x)
          const int f = axis == 0 ? (sign < 0 ? 5 : 3) : axis == 1 ? (sign < 0 ? 2 : 4) : (sign < 0 ? 0 : 1);
          const Quad q = hex_face(out.mesh.hexes[h], f);
          Vec3 centre = Vec3::Zero();
          for (int v : q) centre += out.mesh.vertices[idx(v)] / 4.0;
          faces.push_back({q, (centre - cube.centre).normalized()});
        }
  cube.faces = std::move(faces);
}

Vec3 quad_centre(const HexMesh& m, const Quad& q) {
  Vec3 c = Vec3::Zero();
  for (int v : q) c += m.vertices[idx(v)] / 4.0;
  return c;
}

Vec3 quad_normal(const HexMesh& m, const Quad& q) {
  const auto& p = m.vertices;
  return (p[idx(q[2])] - p[idx(q[0])]).cross(p[idx(q[3])] - p[idx(q[1])]).normalized();
}

//! Unit directions from the centre to the corners, perpendicular to t.
std::array<Vec3, 4> corner_directions(const HexMesh& m, const Quad& q, const Vec3& t) {
  const Vec3 c = quad_centre(m, q);
  std::array<Vec3, 4> u;
  for (std::size_t k = 0; k < 4; ++k) {
    Vec3 d = m.vertices[idx(q[k])] - c;
    d -= d.dot(t) * t;
    u[k] = d.normalized();
  }
  return u;
}

double signed_angle(const Vec3& a, const Vec3& b, const Vec3& axis) {
  return std::atan2(a.cross(b).dot(axis), a.dot(b));
}

//! Shift s of `target` (corner k of the transported section goes to
//! target[(k + s) % 4]) with the least twist, and that twist (radians, about t).
std::pair<int, double> best_shift(const std::array<Vec3, 4>& u, const std::array<Vec3, 4>& w, const Vec3& t) {
  int best = 0;
  double best_cost = 1e300, best_twist = 0;
  for (int s = 0; s < 4; ++s) {
    double sn = 0, cs = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      const double a = signed_angle(u[k], w[(k + idx(s)) % 4], t);
      sn += std::sin(a), cs += std::cos(a);
    }
    const double twist = std::atan2(sn, cs);
    if (std::abs(twist) < best_cost - 1e-12) best_cost = std::abs(twist), best = s, best_twist = twist;
  }
  return {best, best_twist};
}

//! Adds a tube through the section centres `centres` (radii `radii`), from
//! the quad `start` (right-hand normal along the tube) to the quad `end`
//! (same convention; nullptr for a closed tube that returns to its first
//! section, whose corners are then built from `start_dirs`).
void add_tube(const std::vector<Vec3>& centres, const std::vector<double>& half_diagonals, const Quad* start,
              const Quad* end, int arc, TubularStructure& out) {
  HexMesh& m = out.mesh;
  const std::size_t L = centres.size();
  const bool closed = start == nullptr;
  // tangents: from the neighbouring centres (or the end quads)
  std::vector<Vec3> all = centres;
  if (!closed) {
    all.insert(all.begin(), quad_centre(m, *start));
    all.push_back(quad_centre(m, *end));
  }
  auto tangent_at = [&](std::size_t i) -> Vec3 {  // i indexes `centres`
    if (closed) return (centres[(i + 1) % L] - centres[(i + L - 1) % L]).normalized();
    return (all[i + 2] - all[i]).normalized();
  };
  Vec3 t = closed ? tangent_at(0) : quad_normal(m, *start);
  std::array<Vec3, 4> u;
  Quad first;
  std::size_t from = 0;
  if (closed) {
    u[0] = any_perpendicular(t);
    u[1] = t.cross(u[0]);
    u[2] = -u[0];
    u[3] = -u[1];
    for (std::size_t k = 0; k < 4; ++k) {
      first[k] = static_cast<int>(m.vertices.size());
      m.vertices.push_back(centres[0] + half_diagonals[0] * u[k]);
      out.vertex_anchor.push_back(centres[0]);
    }
    from = 1;
  } else {
    first = *start;
    u = corner_directions(m, first, t);
  }
  // transport the corner directions along the sections, then to the end
  std::vector<std::array<Vec3, 4>> dirs(L);
  std::vector<Vec3> tangents(L);
  if (closed) dirs[0] = u, tangents[0] = t;
  for (std::size_t i = from; i < L; ++i) {
    const Vec3 ti = tangent_at(i);
    const Eigen::Quaterniond r = Eigen::Quaterniond::FromTwoVectors(t, ti);
    for (auto& d : u) d = (r * d).normalized();
    t = ti;
    dirs[i] = u, tangents[i] = t;
  }
  Vec3 t_end = closed ? tangents[0] : -quad_normal(m, *end);
  {
    const Eigen::Quaterniond r = Eigen::Quaterniond::FromTwoVectors(t, t_end);
    for (auto& d : u) d = (r * d).normalized();
  }
  const Quad last_quad = closed ? first : Quad{(*end)[0], (*end)[3], (*end)[2], (*end)[1]};
  const std::array<Vec3, 4> w = closed ? dirs[0] : corner_directions(m, last_quad, t_end);
  const auto [shift, twist] = best_shift(u, w, t_end);
  Quad last;
  for (std::size_t k = 0; k < 4; ++k) last[k] = last_quad[(k + idx(shift)) % 4];
  // sections with the twist spread evenly
  const double steps = static_cast<double>(closed ? L : L + 1);
  Quad prev = first;
  for (std::size_t i = from; i < L; ++i) {
    const double angle = twist * static_cast<double>(closed ? i : i + 1) / steps;
    const Eigen::AngleAxisd rot(angle, tangents[i]);
    Quad section;
    for (std::size_t k = 0; k < 4; ++k) {
      section[k] = static_cast<int>(m.vertices.size());
      m.vertices.push_back(centres[i] + half_diagonals[i] * (rot * dirs[i][k]));
      out.vertex_anchor.push_back(centres[i]);
    }
    m.hexes.push_back({prev[0], prev[1], prev[2], prev[3], section[0], section[1], section[2], section[3]});
    out.hex_node.push_back(-1);
    out.hex_arc.push_back(arc);
    prev = section;
  }
  m.hexes.push_back({prev[0], prev[1], prev[2], prev[3], last[0], last[1], last[2], last[3]});
  out.hex_node.push_back(-1);
  out.hex_arc.push_back(arc);
}

}  // namespace

TubularStructure build_tubular_structure(const Skeleton& skeleton, const TubularStructureOptions& options) {
  if (skeleton.num_nodes() == 0) throw InvalidArgumentError("build_tubular_structure: the skeleton has no node");
  check_skeleton(skeleton);
  TubularStructure out;
  const auto arcs = skeleton_arcs(skeleton);
  const std::size_t n = skeleton.num_nodes();
  std::vector<std::vector<ArcEnd>> ends(n);
  for (std::size_t a = 0; a < arcs.size(); ++a) {
    const auto& nodes = arcs[a].nodes;
    if (arcs[a].closed) continue;
    const Vec3& p0 = skeleton.points[idx(nodes[0])];
    const Vec3& pn = skeleton.points[idx(nodes.back())];
    ends[idx(nodes[0])].push_back({static_cast<int>(a), true, (skeleton.points[idx(nodes[1])] - p0).normalized()});
    ends[idx(nodes.back())].push_back(
        {static_cast<int>(a), false, (skeleton.points[idx(nodes[nodes.size() - 2])] - pn).normalized()});
  }
  // cubes
  std::vector<Cube> cubes(n);
  std::vector<std::vector<int>> end_face(n);  // per node, per end: face index
  double worst_dot = 1;
  for (std::size_t v = 0; v < n; ++v) {
    const std::size_t degree = skeleton.neighbors[v].size();
    if (degree == 2) continue;
    Cube& cube = cubes[v];
    cube.centre = skeleton.points[v];
    // no wider than the thinnest arc it meets, so that each face fits its tube
    double radius = skeleton.radii[v];
    for (const ArcEnd& e : ends[v]) {
      const auto& nodes = arcs[idx(e.arc)].nodes;
      radius = std::min(radius, skeleton.radii[idx(e.at_front ? nodes[1] : nodes[nodes.size() - 2])]);
    }
    cube.half = options.core_scale * radius;
    const auto frames = candidate_frames(ends[v]);
    Assignment best;
    for (int sub = 1;; ++sub) {
      if (6u * idx(sub * sub) < ends[v].size()) continue;
      for (const auto& frame : frames) {
        const Assignment a = assign(ends[v], face_directions(frame, sub));
        if (a.better_than(best)) best = a, cube.frame = frame, cube.n = sub;
      }
      if (best.worst >= options.min_dot || sub >= 4) break;
    }
    worst_dot = std::min(worst_dot, best.worst);
    add_cube(cube, static_cast<int>(v), out);
    end_face[v] = best.face;
    ++out.num_cubes;
    out.num_subdivided_cubes += cube.n > 1;
  }
  out.worst_arc_angle_deg = std::acos(std::clamp(worst_dot, -1.0, 1.0)) * 180 / std::numbers::pi;
  auto face_of = [&](int node, int arc, bool front) -> const FaceQuad& {
    const auto& e = ends[idx(node)];
    for (std::size_t i = 0; i < e.size(); ++i)
      if (e[i].arc == arc && e[i].at_front == front) return cubes[idx(node)].faces[idx(end_face[idx(node)][i])];
    throw AlgorithmError("build_tubular_structure: an arc end has no face (internal error)");
  };
  // tubes
  for (std::size_t a = 0; a < arcs.size(); ++a) {
    const auto& nodes = arcs[a].nodes;
    std::vector<Vec3> centres;
    std::vector<double> diag;
    if (arcs[a].closed) {
      for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
        centres.push_back(skeleton.points[idx(nodes[i])]);
        diag.push_back(options.core_scale * skeleton.radii[idx(nodes[i])] * std::sqrt(2.0));
      }
      add_tube(centres, diag, nullptr, nullptr, static_cast<int>(a), out);
      ++out.num_tubes;
      continue;
    }
    const FaceQuad& f0 = face_of(nodes.front(), static_cast<int>(a), true);
    const FaceQuad& f1 = face_of(nodes.back(), static_cast<int>(a), false);
    const Cube& c0 = cubes[idx(nodes.front())];
    const Cube& c1 = cubes[idx(nodes.back())];
    const Vec3 n0 = quad_normal(out.mesh, f0.quad), n1 = quad_normal(out.mesh, f1.quad);
    const Vec3 q0 = quad_centre(out.mesh, f0.quad), q1 = quad_centre(out.mesh, f1.quad);
    // skip the inner nodes at each end that are still inside (or just out of) the cubes
    const double need = options.clearance - 1.0;
    std::size_t lo = 1, hi = nodes.size() - 2;  // inner nodes lo..hi
    while (lo <= hi && (skeleton.points[idx(nodes[lo])] - q0).dot(n0) < need * c0.half) ++lo;
    while (hi >= lo && (skeleton.points[idx(nodes[hi])] - q1).dot(n1) < need * c1.half) --hi;
    if (lo > hi) {
      // no node clear of both cubes: keep the middle one if it is at least in
      // front of both faces (always on a loop back to the same cube), else
      // join the two faces by one hexahedron (a section behind a face turns
      // its layer inside out: bob's short tail)
      const std::size_t mid = nodes.size() / 2;
      const Vec3& p = skeleton.points[idx(nodes[mid])];
      const bool in_front = (p - q0).dot(n0) > 0 && (p - q1).dot(n1) > 0;
      if (in_front || nodes.front() == nodes.back()) lo = hi = mid;
    }
    for (std::size_t i = lo; i <= hi && i + 1 < nodes.size() && i >= 1; ++i) {
      centres.push_back(skeleton.points[idx(nodes[i])]);
      diag.push_back(options.core_scale * skeleton.radii[idx(nodes[i])] * std::sqrt(2.0));
    }
    add_tube(centres, diag, &f0.quad, &f1.quad, static_cast<int>(a), out);
    ++out.num_tubes;
  }
  return out;
}

}  // namespace subfab
