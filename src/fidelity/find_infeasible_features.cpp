// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/fidelity/find_infeasible_features.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>

#include "geometry/exact_normal_signs.h"
#include "geometry/triangle_meets_open_box.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

using Signs = std::array<std::int8_t, 3>;

int sign_of_difference(double a, double b) { return a > b ? 1 : (a < b ? -1 : 0); }

//! Does a face with exact normal signs s face axis a (n.a >= 0)?
bool faces_axis(const Signs& s, int axis) {
  const int dim = axis / 2;
  const int sign = axis % 2 == 0 ? 1 : -1;
  return sign * s[static_cast<std::size_t>(dim)] >= 0;
}

//! Bit mask of the axes (kAllAxes order) a face faces.
unsigned facing_mask(const Signs& s) {
  unsigned m = 0;
  for (int a = 0; a < 6; ++a)
    if (faces_axis(s, a)) m |= 1u << a;
  return m;
}

//! Vertex -> incident faces (CSR, faces in increasing id).
struct Stars {
  std::vector<std::size_t> offset;
  std::vector<int> faces;
  explicit Stars(const Mesh& mesh) : offset(mesh.num_vertices() + 1, 0) {
    for (const auto& t : mesh.faces)
      for (int v : t) ++offset[static_cast<std::size_t>(v) + 1];
    for (std::size_t v = 0; v < mesh.num_vertices(); ++v) offset[v + 1] += offset[v];
    faces.resize(offset.back());
    std::vector<std::size_t> fill(offset.begin(), offset.end() - 1);
    for (std::size_t f = 0; f < mesh.num_faces(); ++f)
      for (int v : mesh.faces[f]) faces[fill[static_cast<std::size_t>(v)]++] = static_cast<int>(f);
  }
  std::size_t begin(std::size_t v) const { return offset[v]; }
  std::size_t end(std::size_t v) const { return offset[v + 1]; }
};

//! Position (0..2) of vertex v in triangle t, or -1.
int corner_of(const Triangle& t, int v) {
  for (int i = 0; i < 3; ++i)
    if (t[static_cast<std::size_t>(i)] == v) return i;
  return -1;
}

//! Side of the cone in one coordinate: +1 = [0, inf), -1 = (-inf, 0], 0 = both.
//! From the signs of the cone's generators in that coordinate; when all are 0
//! (the face lies in that coordinate plane) the side of the solid, opposite
//! to the normal component.
int cone_side(int s1, int s2, int normal_sign) {
  if (s1 >= 0 && s2 >= 0 && (s1 > 0 || s2 > 0)) return 1;
  if (s1 <= 0 && s2 <= 0 && (s1 < 0 || s2 < 0)) return -1;
  if (s1 == 0 && s2 == 0) return -normal_sign;  // 0 for a degenerate face: both sides
  return 0;
}

//! Edge test for face f (third vertex w) across the edge (u, v) from g (third
//! vertex wg): true when g meets the open cone of f's half-plane at the edge.
bool neighbour_meets_edge_cone(const Vec3& u, const Vec3& v, const Vec3& w, const Vec3& wg, const Signs& nf) {
  for (int k = 0; k < 3; ++k) {
    if (u[k] != v[k]) continue;  // the cone spans the whole line in k
    const int side = cone_side(sign_of_difference(w[k], u[k]), 0, nf[static_cast<std::size_t>(k)]);
    if (side == 0) continue;
    if (sign_of_difference(wg[k], u[k]) != side) return false;
  }
  return true;
}

struct VertexScan {
  std::vector<InfeasibleFeature> edges;   // edges (u, v) with u = this vertex < v
  std::optional<InfeasibleFeature> vertex;
};

}  // namespace

FeasibilityResult find_infeasible_features(const Mesh& mesh, const FeasibilityOptions& options) {
  const Stars stars(mesh);
  const bool local = !options.only_vertices.empty();
  // The vertices scanned (all, or the local region, sorted and unique).
  std::vector<int> scanned = options.only_vertices;
  if (local) {
    std::sort(scanned.begin(), scanned.end());
    scanned.erase(std::unique(scanned.begin(), scanned.end()), scanned.end());
    if (scanned.front() < 0 || static_cast<std::size_t>(scanned.back()) >= mesh.num_vertices())
      throw InvalidArgumentError("find_infeasible_features: a vertex id of the local region is out of range");
  } else {
    scanned.resize(mesh.num_vertices());
    for (std::size_t v = 0; v < scanned.size(); ++v) scanned[v] = static_cast<int>(v);
  }
  std::vector<char> in_region(local ? mesh.num_vertices() : 0, 0);
  for (int v : options.only_vertices) in_region[static_cast<std::size_t>(v)] = 1;
  // Exact normal signs of the faces around the scanned vertices (all faces for the whole mesh).
  std::vector<Signs> signs;
  if (local) {
    signs.resize(mesh.num_faces());
    for (int v : scanned)
      for (std::size_t i = stars.begin(static_cast<std::size_t>(v)); i < stars.end(static_cast<std::size_t>(v)); ++i) {
        const Triangle& t = mesh.faces[static_cast<std::size_t>(stars.faces[i])];
        signs[static_cast<std::size_t>(stars.faces[i])] = detail::exact_normal_signs(
            mesh.vertices[static_cast<std::size_t>(t[0])], mesh.vertices[static_cast<std::size_t>(t[1])],
            mesh.vertices[static_cast<std::size_t>(t[2])]);
      }
  } else {
    signs = detail::exact_normal_signs(mesh);
  }
  std::vector<unsigned> mask(mesh.num_faces());
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) mask[f] = facing_mask(signs[f]);
  if (const std::vector<std::uint8_t>* allowed = options.allowed_overhangs) {
    if (allowed->size() != mesh.num_faces())
      throw InvalidArgumentError("find_infeasible_features: allowed_overhangs has " + std::to_string(allowed->size()) +
                                 " entries for " + std::to_string(mesh.num_faces()) + " faces");
    // Bit k allows both directions along axis k (kAllAxes order: +x, -x, +y, ...).
    for (std::size_t f = 0; f < mesh.num_faces(); ++f)
      for (unsigned k = 0; k < 3; ++k)
        if (((*allowed)[f] >> k) & 1u) mask[f] |= 3u << (2 * k);
  }
  const auto vertex = [&](int v) -> const Vec3& { return mesh.vertices[static_cast<std::size_t>(v)]; };

  std::vector<VertexScan> scans(scanned.size());
  std::vector<int> bad_edge_vertex(scanned.size(), -1);  // first vertex with an open edge (error)
  parallel_for(
      0, scanned.size(),
      [&](std::size_t si) {
        const int p = scanned[si];
        const std::size_t pi = static_cast<std::size_t>(p);
        VertexScan& scan = scans[si];
        // --- Edges (p, q) with p < q: f has p -> q, g has q -> p.
        if (options.check_edges) {
          for (std::size_t i = stars.begin(pi); i < stars.end(pi); ++i) {
            const int f = stars.faces[i];
            const Triangle& tf = mesh.faces[static_cast<std::size_t>(f)];
            const int c = corner_of(tf, p);
            const int q = tf[static_cast<std::size_t>((c + 1) % 3)];
            int g = -1;
            for (std::size_t j = stars.begin(pi); j < stars.end(pi) && g < 0; ++j) {
              const Triangle& tg = mesh.faces[static_cast<std::size_t>(stars.faces[j])];
              const int cg = corner_of(tg, p);
              if (tg[static_cast<std::size_t>((cg + 2) % 3)] == q) g = stars.faces[j];
            }
            if (g < 0) {
              bad_edge_vertex[si] = p;
              continue;
            }
            if (q < p && (!local || in_region[static_cast<std::size_t>(q)])) continue;  // tested from q
            const Triangle& tg = mesh.faces[static_cast<std::size_t>(g)];
            const Vec3& w = vertex(tf[static_cast<std::size_t>((c + 2) % 3)]);
            const Vec3& wg = vertex(tg[static_cast<std::size_t>((corner_of(tg, p) + 1) % 3)]);
            if ((mask[static_cast<std::size_t>(f)] & mask[static_cast<std::size_t>(g)]) != 0) continue;
            const bool f_blocked = neighbour_meets_edge_cone(vertex(p), vertex(q), w, wg, signs[static_cast<std::size_t>(f)]);
            const bool g_blocked = neighbour_meets_edge_cone(vertex(p), vertex(q), wg, w, signs[static_cast<std::size_t>(g)]);
            if (!f_blocked && !g_blocked) continue;
            InfeasibleFeature e;
            e.kind = InfeasibleFeature::Kind::Edge;
            e.vertex0 = std::min(p, q);  // q < p only for an edge leaving the local region
            e.vertex1 = std::max(p, q);
            e.face = f_blocked && g_blocked ? std::min(f, g) : (f_blocked ? f : g);
            e.blocking_face = e.face == f ? g : f;
            scan.edges.push_back(e);
          }
          std::sort(scan.edges.begin(), scan.edges.end(),
                    [](const InfeasibleFeature& a, const InfeasibleFeature& b) { return a.vertex1 < b.vertex1; });
        }
        // --- Vertex p: the corner of each star face.
        if (!options.check_vertices) return;
        const Vec3& pp = vertex(p);
        // Is every axis f faces blocked by a star face facing away from it
        // that meets the open box?
        const auto corner_blocked = [&](const Box3& box, int f, int* blocker) {
          unsigned open = mask[static_cast<std::size_t>(f)];  // axes not yet blocked
          for (std::size_t j = stars.begin(pi); j < stars.end(pi) && open != 0; ++j) {
            const int h = stars.faces[j];
            const unsigned away = open & ~mask[static_cast<std::size_t>(h)];
            if (h == f || away == 0) continue;
            const Triangle& th = mesh.faces[static_cast<std::size_t>(h)];
            if (!detail::triangle_meets_open_box(vertex(th[0]), vertex(th[1]), vertex(th[2]), box)) continue;
            open &= ~away;
            *blocker = h;
          }
          return open == 0;
        };
        bool splittable = true;  // every blocked corner here is coverable once split
        for (std::size_t i = stars.begin(pi); i < stars.end(pi) && splittable; ++i) {
          const int f = stars.faces[i];
          const Triangle& tf = mesh.faces[static_cast<std::size_t>(f)];
          const int c = corner_of(tf, p);
          const Vec3& q = vertex(tf[static_cast<std::size_t>((c + 1) % 3)]);
          const Vec3& r = vertex(tf[static_cast<std::size_t>((c + 2) % 3)]);
          Box3 box;
          for (int k = 0; k < 3; ++k) {
            const int side = cone_side(sign_of_difference(q[k], pp[k]), sign_of_difference(r[k], pp[k]),
                                       signs[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)]);
            const double reach = std::max(1.0, std::abs(pp[k]));  // any positive extent gives the same answer
            box.min[k] = side > 0 ? pp[k] : pp[k] - reach;
            box.max[k] = side < 0 ? pp[k] : pp[k] + reach;
          }
          int blocker = -1;
          if (!corner_blocked(box, f, &blocker)) continue;
          // The corner split along the coordinate planes through p: each
          // piece lies in one closed orthant (its smallest cone).
          bool all_pieces_ok = true;
          std::array<bool, 3> flat{};
          for (int k = 0; k < 3; ++k) flat[static_cast<std::size_t>(k)] = q[k] == pp[k] && r[k] == pp[k];
          for (int pattern = 0; pattern < 8 && all_pieces_ok; ++pattern) {
            Box3 orthant = box, probe = box;
            bool skip = false;
            for (int k = 0; k < 3; ++k) {
              const int side = (pattern >> k) & 1 ? 1 : -1;
              const double reach = std::max(1.0, std::abs(pp[k]));
              if (flat[static_cast<std::size_t>(k)]) {  // keep the solid side; probe both sides
                skip = skip || side > 0;
                probe.min[k] = pp[k] - reach;
                probe.max[k] = pp[k] + reach;
                continue;
              }
              orthant.min[k] = probe.min[k] = side > 0 ? pp[k] : pp[k] - reach;
              orthant.max[k] = probe.max[k] = side < 0 ? pp[k] : pp[k] + reach;
            }
            if (skip || !detail::triangle_meets_open_box(pp, q, r, probe)) continue;  // f has no piece there
            int unused = -1;
            all_pieces_ok = !corner_blocked(orthant, f, &unused);
          }
          splittable = all_pieces_ok;
          if (scan.vertex && splittable) continue;
          InfeasibleFeature e;
          e.kind = InfeasibleFeature::Kind::Vertex;
          e.vertex0 = p;
          e.face = f;
          e.blocking_face = blocker;
          scan.vertex = e;
        }
        if (scan.vertex) scan.vertex->splittable = splittable;
      },
      256);

  for (int v : bad_edge_vertex)
    if (v >= 0)
      throw InvalidMeshError("find_infeasible_features: an edge at vertex " + std::to_string(v) +
                             " has no opposite edge (the mesh is not closed and consistently oriented)");
  FeasibilityResult result;
  for (const VertexScan& s : scans) {
    result.features.insert(result.features.end(), s.edges.begin(), s.edges.end());
    result.num_edges += s.edges.size();
  }
  for (const VertexScan& s : scans)
    if (s.vertex) {
      result.features.push_back(*s.vertex);
      ++result.num_vertices;
      if (s.vertex->splittable) ++result.num_splittable_vertices;
    }
  return result;
}

std::string describe_infeasible_features(const FeasibilityResult& result, const Mesh& positions,
                                         std::size_t max_listed) {
  std::ostringstream out;
  out.precision(6);
  const auto point = [&](int v) {
    const Vec3& p = positions.vertices[static_cast<std::size_t>(v)];
    out << '(' << p.x() << ' ' << p.y() << ' ' << p.z() << ')';
  };
  std::size_t n = 0;
  for (const InfeasibleFeature& f : result.features) {
    if (n == max_listed) break;
    if (n++ > 0) out << ", ";
    if (f.kind == InfeasibleFeature::Kind::Edge) {
      out << "edge ";
      point(f.vertex0);
      out << '-';
      point(f.vertex1);
    } else {
      out << "vertex ";
      point(f.vertex0);
    }
  }
  if (result.features.size() > n) out << ", ...";
  return out.str();
}

}  // namespace subfab
