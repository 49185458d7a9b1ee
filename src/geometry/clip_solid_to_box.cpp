// SPDX-License-Identifier: GPL-3.0-or-later
// solid ∩ box, exactly, as closed 2-manifold pieces: the clip step of
// carving (thesis Section 4.3.3), see clip_solid_to_box.h.
#include "geometry/clip_solid_to_box.h"

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <utility>

#include "subfab/core/error.h"

namespace subfab::detail {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using FT = ExactKernel::FT;

bool in_closed_box(const ExactPoint& p, const Box3& b) {
  for (int k = 0; k < 3; ++k)
    if (p[k] < FT(b.min[k]) || p[k] > FT(b.max[k])) return false;
  return true;
}

//! Sign of component k of (b - a) x (c - a), exact.
int normal_sign(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c, int k) {
  const auto n = CGAL::cross_product(b - a, c - a);
  return static_cast<int>(CGAL::sign(n[k]));
}

//! Keep a face of the (corefined) solid patch? Its three corners lie in the
//! closed box; a face lying in a box plane is kept only when its outward
//! normal leaves the box through that plane (the solid is on the box side).
bool keep_patch_face(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c, const Box3& box) {
  if (!in_closed_box(a, box) || !in_closed_box(b, box) || !in_closed_box(c, box)) return false;
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side < 2; ++side) {
      const FT plane(side == 0 ? box.min[k] : box.max[k]);
      if (a[k] == plane && b[k] == plane && c[k] == plane) return normal_sign(a, b, c, k) == (side == 0 ? -1 : 1);
    }
  return true;
}

//! Is the open triangle (u, v, w) of a box face, whose edge (u, v) is an
//! edge of the solid surface, inside the solid near that edge? (u, v) is
//! shared by the solid faces (u, v, a) and (v, u, b), outward oriented; the
//! solid occupies the dihedral wedge between them on their inner sides.
//! Points on the faces themselves (a box face coinciding with the surface)
//! count as outside.
bool inside_wedge(const ExactPoint& u, const ExactPoint& v, const ExactPoint& a, const ExactPoint& b,
                  const ExactPoint& w) {
  const bool convex = CGAL::orientation(u, v, a, b) == CGAL::NEGATIVE;
  const auto s1 = CGAL::orientation(u, v, a, w);
  const auto s2 = CGAL::orientation(v, u, b, w);
  if (convex) return s1 == CGAL::NEGATIVE && s2 == CGAL::NEGATIVE;
  return s1 == CGAL::NEGATIVE || s2 == CGAL::NEGATIVE;
}

//! Triangle soup of one clipped solid, with exact shared corners.
struct Soup {
  std::vector<ExactPoint> points;
  std::vector<std::array<std::size_t, 3>> faces;
  std::map<ExactPoint, std::size_t, ExactPointLess> index;
  std::size_t add(const ExactPoint& p) {
    auto [it, inserted] = index.emplace(p, points.size());
    if (inserted) points.push_back(p);
    return it->second;
  }
};

std::size_t find_root(std::vector<std::size_t>& parent, std::size_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

//! Splits a closed, consistently oriented soup into closed 2-manifold
//! pieces. Where k > 1 pieces of the soup meet along an edge (2k faces on
//! it), each face is paired with the face across the solid wedge it bounds
//! (exact angular order around the edge); corners are then grouped into
//! umbrellas, and each umbrella gets its own vertex, so pieces that touch
//! along an edge or at a vertex come out as separate closed meshes.
std::vector<ExactMesh> split_soup(const Soup& soup) {
  const std::size_t nf = soup.faces.size();
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> directed;
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      directed[{soup.faces[f][static_cast<std::size_t>(k)], soup.faces[f][static_cast<std::size_t>((k + 1) % 3)]}]
          .push_back(f);
  auto third = [&](std::size_t f, std::size_t a, std::size_t b) {
    for (std::size_t v : soup.faces[f])
      if (v != a && v != b) return v;
    throw AlgorithmError("carving produced a degenerate face");
  };
  // partner[3 f + k]: the face across directed edge k of face f.
  std::vector<std::size_t> partner(3 * nf, nf);
  for (const auto& [edge, out] : directed) {
    auto it = directed.find({edge.second, edge.first});
    if (it == directed.end() || it->second.size() != out.size())
      throw AlgorithmError("carving produced a surface that is not closed (an exact boolean failed)");
    const std::vector<std::size_t>& in = it->second;
    std::vector<std::size_t> chosen(out.size(), nf);
    if (out.size() == 1) {
      chosen[0] = in[0];
    } else {
      // Rotating the half-plane of an outgoing face (u -> v, w) about
      // d = v - u in the negative sense sweeps the solid it bounds first.
      const ExactPoint& u = soup.points[edge.first];
      const ExactPoint& v = soup.points[edge.second];
      const auto d = v - u;
      auto perp = [&](std::size_t f) {
        const auto x = soup.points[third(f, edge.first, edge.second)] - u;
        return x - (x * d) / (d * d) * d;
      };
      for (std::size_t i = 0; i < out.size(); ++i) {
        const auto r = perp(out[i]);
        // Clockwise angle from r: half 0 = [0, pi), half 1 = [pi, 2 pi).
        auto half = [&](const ExactKernel::Vector_3& x) {
          const auto s = -(d * CGAL::cross_product(r, x));
          if (CGAL::is_positive(s)) return 0;
          if (CGAL::is_zero(s) && CGAL::is_positive(r * x)) return 0;
          return 1;
        };
        std::size_t best = nf;
        ExactKernel::Vector_3 best_x;
        int best_half = 2;
        for (std::size_t g : in) {
          const auto x = perp(g);
          const int h = half(x);
          bool better = best == nf || h < best_half;
          if (!better && h == best_half) better = CGAL::is_positive(-(d * CGAL::cross_product(x, best_x)));
          if (better) {
            best = g;
            best_x = x;
            best_half = h;
          }
        }
        chosen[i] = best;
      }
      std::vector<std::size_t> sorted = chosen;
      std::sort(sorted.begin(), sorted.end());
      std::vector<std::size_t> expected = in;
      std::sort(expected.begin(), expected.end());
      if (sorted != expected)
        throw AlgorithmError("carving could not pair the faces around a non-manifold edge of a block");
    }
    for (std::size_t i = 0; i < out.size(); ++i) {
      const std::size_t f = out[i];
      for (int k = 0; k < 3; ++k)
        if (soup.faces[f][static_cast<std::size_t>(k)] == edge.first &&
            soup.faces[f][static_cast<std::size_t>((k + 1) % 3)] == edge.second)
          partner[3 * f + static_cast<std::size_t>(k)] = chosen[i];
    }
  }
  // Pieces: faces joined across paired edges; umbrellas: corners joined
  // across the outgoing edge of the corner.
  std::vector<std::size_t> face_parent(nf), corner_parent(3 * nf);
  std::iota(face_parent.begin(), face_parent.end(), std::size_t{0});
  std::iota(corner_parent.begin(), corner_parent.end(), std::size_t{0});
  for (std::size_t f = 0; f < nf; ++f)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t g = partner[3 * f + k];
      face_parent[find_root(face_parent, f)] = find_root(face_parent, g);
      const std::size_t v = soup.faces[f][k];
      for (std::size_t j = 0; j < 3; ++j)
        if (soup.faces[g][j] == v) corner_parent[find_root(corner_parent, 3 * f + k)] = find_root(corner_parent, 3 * g + j);
    }
  std::vector<std::size_t> piece_of(nf, nf);
  std::vector<ExactMesh> pieces;
  std::vector<std::map<std::size_t, VertexIndex>> vertex_maps;
  for (std::size_t f = 0; f < nf; ++f) {
    const std::size_t root = find_root(face_parent, f);
    if (piece_of[root] == nf) {
      piece_of[root] = pieces.size();
      pieces.emplace_back();
      vertex_maps.emplace_back();
    }
    const std::size_t p = piece_of[root];
    std::array<VertexIndex, 3> vs;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t c = find_root(corner_parent, 3 * f + k);
      auto [it, inserted] = vertex_maps[p].emplace(c, VertexIndex());
      if (inserted) it->second = pieces[p].add_vertex(soup.points[soup.faces[f][k]]);
      vs[k] = it->second;
    }
    if (pieces[p].add_face(vs[0], vs[1], vs[2]) == ExactMesh::null_face())
      throw AlgorithmError("carving produced a block that cannot be made a 2-manifold");
  }
  return pieces;
}

}  // namespace

std::vector<ExactMesh> clip_solid_to_box(const Mesh& solid, const SolidIndex& index, const Box3& box) {
  std::vector<ExactMesh> out;
  if (box.volume() <= 0.0) return out;
  const std::vector<int> near = index.faces_near_closed_box(box);
  if (near.empty()) {
    if (index.is_inside(box.min)) out.push_back(detail::box_mesh(box));
    return out;
  }
  ExactMesh patch;
  {
    std::map<int, VertexIndex> vmap;
    for (int f : near) {
      std::array<VertexIndex, 3> vs;
      for (std::size_t k = 0; k < 3; ++k) {
        const int v = solid.faces[static_cast<std::size_t>(f)][k];
        auto [it, inserted] = vmap.emplace(v, VertexIndex());
        if (inserted) {
          const Vec3& p = solid.vertices[static_cast<std::size_t>(v)];
          it->second = patch.add_vertex(ExactPoint(p.x(), p.y(), p.z()));
        }
        vs[k] = it->second;
      }
      if (patch.add_face(vs[0], vs[1], vs[2]) == ExactMesh::null_face()) {
        patch = detail::to_exact(solid);  // the local patch is not a surface: use the whole solid
        break;
      }
    }
  }
  ExactMesh cutter = detail::box_mesh(box);
  auto patch_ecm = patch.add_property_map<EdgeIndex, bool>("e:constrained", false).first;
  auto cutter_ecm = cutter.add_property_map<EdgeIndex, bool>("e:constrained", false).first;
  PMP::corefine(patch, cutter, CGAL::parameters::edge_is_constrained_map(patch_ecm),
                CGAL::parameters::edge_is_constrained_map(cutter_ecm));

  Soup soup;
  for (FaceIndex f : patch.faces()) {
    const HalfedgeIndex h = patch.halfedge(f);
    const VertexIndex a = patch.source(h), b = patch.target(h), c = patch.target(patch.next(h));
    if (!keep_patch_face(patch.point(a), patch.point(b), patch.point(c), box)) continue;
    soup.faces.push_back({soup.add(patch.point(a)), soup.add(patch.point(b)), soup.add(patch.point(c))});
  }
  // Patch vertices on the box surface, to find the patch edge of a cut edge.
  std::map<ExactPoint, VertexIndex, ExactPointLess> on_box;
  for (VertexIndex v : patch.vertices()) {
    const ExactPoint& p = patch.point(v);
    if (!in_closed_box(p, box)) continue;
    bool on_plane = false;
    for (int k = 0; k < 3 && !on_plane; ++k) on_plane = p[k] == FT(box.min[k]) || p[k] == FT(box.max[k]);
    if (on_plane) on_box.emplace(p, v);
  }
  auto fcc = cutter.add_property_map<FaceIndex, std::size_t>("f:region", 0).first;
  const std::size_t num_regions =
      PMP::connected_components(cutter, fcc, CGAL::parameters::edge_is_constrained_map(cutter_ecm));
  std::vector<int> region_inside(num_regions, -1);
  for (FaceIndex f : cutter.faces()) {
    int& state = region_inside[fcc[f]];
    if (state >= 0) continue;
    for (HalfedgeIndex h : CGAL::halfedges_around_face(cutter.halfedge(f), cutter)) {
      if (!cutter_ecm[cutter.edge(h)]) continue;
      const ExactPoint& u = cutter.point(cutter.source(h));
      const ExactPoint& v = cutter.point(cutter.target(h));
      const ExactPoint& w = cutter.point(cutter.target(cutter.next(h)));
      auto iu = on_box.find(u), iv = on_box.find(v);
      if (iu == on_box.end() || iv == on_box.end()) continue;
      const auto [ph, found] = CGAL::halfedge(iu->second, iv->second, patch);
      if (!found || patch.is_border(ph) || patch.is_border(patch.opposite(ph))) continue;
      const ExactPoint& a = patch.point(patch.target(patch.next(ph)));
      const ExactPoint& b = patch.point(patch.target(patch.next(patch.opposite(ph))));
      state = inside_wedge(u, v, a, b, w) ? 1 : 0;
      break;
    }
  }
  for (std::size_t r = 0; r < num_regions; ++r)
    if (region_inside[r] < 0) {
      // A region with no cut edge is the whole box surface (the solid
      // surface crosses no box face): one exact point test decides it.
      if (num_regions != 1)
        throw AlgorithmError("carving could not classify a region of a box face against the solid");
      region_inside[r] = index.is_inside(box.min) ? 1 : 0;
    }
  for (FaceIndex f : cutter.faces()) {
    if (region_inside[fcc[f]] != 1) continue;
    const HalfedgeIndex h = cutter.halfedge(f);
    soup.faces.push_back({soup.add(cutter.point(cutter.source(h))), soup.add(cutter.point(cutter.target(h))),
                          soup.add(cutter.point(cutter.target(cutter.next(h))))});
  }
  if (soup.faces.empty()) return out;
  return split_soup(soup);
}

}  // namespace subfab::detail
