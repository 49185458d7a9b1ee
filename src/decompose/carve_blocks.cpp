// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/carve_blocks.h"

#include <CGAL/Polygon_mesh_processing/clip.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>
#include <utility>
#include <array>
#include <atomic>
#include <exception>
#include <string>
#include <vector>

#include "geometry/deterministic_arena.h"
#include "geometry/exact_determinant_signs.h"
#include "geometry/exact_mesh.h"
#include "geometry/solid_index.h"
#include "geometry/triangle_meets_closed_box.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/geometry/axis.h"
#include "subfab/validate/validate_decomposition.h"

namespace subfab {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using detail::ExactKernel;
using detail::ExactMesh;
using detail::ExactPoint;
using FT = ExactKernel::FT;

//! The coordinates of the box planes, per axis, that may bound a piece of
//! one region (so that faces lying on them are known to be cut faces).
struct PlaneSet {
  std::array<std::vector<double>, 3> values;
  void add(const Box3& b) {
    for (int k = 0; k < 3; ++k) {
      values[static_cast<std::size_t>(k)].push_back(b.min[k]);
      values[static_cast<std::size_t>(k)].push_back(b.max[k]);
    }
  }
  void add(int k, double value) { values[static_cast<std::size_t>(k)].push_back(value); }
  void finish() {
    for (auto& v : values) {
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
    }
  }
  //! True when the triangle lies in one of the planes (exact).
  bool holds(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c) const {
    for (int k = 0; k < 3; ++k) {
      if (a[k] != b[k] || a[k] != c[k]) continue;
      const auto& v = values[static_cast<std::size_t>(k)];
      // Candidates: the plane values inside the interval approximation.
      const auto approx = a[k].approx();
      auto first = std::lower_bound(v.begin(), v.end(), approx.inf());
      auto last = std::upper_bound(first, v.end(), approx.sup());
      for (auto j = first; j != last; ++j)
        if (a[k] == FT(*j)) return true;
    }
    return false;
  }
};

//! Exact test: does point p lie on the input surface?
bool on_input_surface(const Mesh& solid, const detail::SolidIndex& index, const ExactPoint& p) {
  Box3 near;
  for (int k = 0; k < 3; ++k) {
    const auto approx = p[k].approx();
    near.min[k] = approx.inf();
    near.max[k] = approx.sup();
  }
  for (int f : index.faces_near_closed_box(near)) {
    const Triangle& t = solid.faces[static_cast<std::size_t>(f)];
    const Vec3& a = solid.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = solid.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = solid.vertices[static_cast<std::size_t>(t[2])];
    const ExactKernel::Triangle_3 tri(ExactPoint(a.x(), a.y(), a.z()), ExactPoint(b.x(), b.y(), b.z()),
                                      ExactPoint(c.x(), c.y(), c.z()));
    if (!tri.is_degenerate() && tri.has_on(p)) return true;
  }
  return false;
}

//! Extra planes that cut a box region, per axis (sorted, each strictly
//! inside the box): the pieces on either side become separate blocks.
using Cuts = std::array<std::vector<double>, 3>;

bool is_cut(const Cuts& cuts, int k, double v) {
  const auto& c = cuts[static_cast<std::size_t>(k)];
  return std::binary_search(c.begin(), c.end(), v);
}

//! Cuts region = box \ (union of `holes`) into disjoint boxes (grid cells of
//! the hole planes and of `cuts`, merged into runs along x then y, never
//! across a plane of `cuts`).
std::vector<Box3> region_cells(const Box3& box, const std::vector<Box3>& holes, const Cuts& cuts) {
  std::array<std::vector<double>, 3> planes;
  for (int k = 0; k < 3; ++k) {
    auto& p = planes[static_cast<std::size_t>(k)];
    p = {box.min[k], box.max[k]};
    for (const Box3& h : holes)
      for (double v : {h.min[k], h.max[k]})
        if (v > box.min[k] && v < box.max[k]) p.push_back(v);
    p.insert(p.end(), cuts[static_cast<std::size_t>(k)].begin(), cuts[static_cast<std::size_t>(k)].end());
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
  }
  const std::size_t nx = planes[0].size() - 1, ny = planes[1].size() - 1, nz = planes[2].size() - 1;
  auto cell = [&](std::size_t i, std::size_t j, std::size_t k) {
    Box3 c;
    c.min = Vec3(planes[0][i], planes[1][j], planes[2][k]);
    c.max = Vec3(planes[0][i + 1], planes[1][j + 1], planes[2][k + 1]);
    return c;
  };
  std::vector<Box3> runs;
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < ny; ++j) {
      std::size_t i = 0;
      while (i < nx) {
        auto is_free = [&](std::size_t ii) {
          const Box3 c = cell(ii, j, k);
          const Vec3 center = 0.5 * (c.min + c.max);
          for (const Box3& h : holes)
            if ((center.array() > h.min.array()).all() && (center.array() < h.max.array()).all()) return false;
          return true;
        };
        if (!is_free(i)) {
          ++i;
          continue;
        }
        std::size_t e = i + 1;
        while (e < nx && !is_cut(cuts, 0, planes[0][e]) && is_free(e)) ++e;
        Box3 r = cell(i, j, k);
        r.max.x() = planes[0][e];
        runs.push_back(r);
        i = e;
      }
    }
  // Merge runs with the same x and z extent that are adjacent in y.
  std::vector<Box3> merged;
  for (const Box3& r : runs) {
    bool joined = false;
    for (Box3& m : merged)
      if (m.min.x() == r.min.x() && m.max.x() == r.max.x() && m.min.z() == r.min.z() &&
          m.max.z() == r.max.z() && m.max.y() == r.min.y() && !is_cut(cuts, 1, r.min.y())) {
        m.max.y() = r.max.y();
        joined = true;
        break;
      }
    if (!joined) merged.push_back(r);
  }
  return merged;
}

Box3 make_box3(const Vec3& min, const Vec3& max) {
  Box3 b;
  b.min = min;
  b.max = max;
  return b;
}

ExactKernel::Iso_cuboid_3 to_cuboid(const Box3& b) {
  return {ExactPoint(b.min.x(), b.min.y(), b.min.z()), ExactPoint(b.max.x(), b.max.y(), b.max.z())};
}

using VertexIndex = ExactMesh::Vertex_index;
using FaceIndex = ExactMesh::Face_index;
using HalfedgeIndex = ExactMesh::Halfedge_index;
using EdgeIndex = ExactMesh::Edge_index;

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

struct ExactPointLess {
  bool operator()(const ExactPoint& p, const ExactPoint& q) const {
    return CGAL::compare_xyz(p, q) == CGAL::SMALLER;
  }
};

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

//! solid ∩ box, exactly, as closed 2-manifold pieces (pieces that touch
//! along an edge or at a vertex come out separately). Only the faces near
//! the box are converted and cut: the faces whose bounding box meets the
//! closed box form a patch whose border lies outside the box, the patch is
//! corefined with the box surface, and the block is bounded by the patch
//! faces inside the box plus the regions of the box surface inside the
//! solid (each region decided exactly at one of its border edges, from the
//! two solid faces on that edge).
std::vector<ExactMesh> clip_to_box(const Mesh& solid, const detail::SolidIndex& index, const Box3& box) {
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

//! A face of a box of the carving order: box `box`, plane x_k = min[k]
//! (side -1) or max[k] (side +1).
struct BoxFace {
  std::size_t box = 0;
  int k = 0;
  int side = 0;
  auto key() const { return std::make_tuple(box, k, side); }
  bool operator<(const BoxFace& o) const { return key() < o.key(); }
  bool operator==(const BoxFace& o) const { return key() == o.key(); }
};

//! A contact no axis-aligned cut separated: the faces of the region (of the
//! box itself or of an earlier box) that hold the whole contact.
struct Contact {
  std::vector<BoxFace> faces;
};

//! The per-box work product.
struct BoxPieces {
  std::vector<Mesh> pieces;
  std::size_t num_dropped = 0;
  bool split_region = false;
  std::size_t num_pinch_cuts = 0;  // planes cut through pinch points
  std::size_t num_unresolved_pinches = 0;  // pinch points no cut separated
  std::vector<Contact> contacts;   // the region faces holding them
  detail::RoundingReport rounding;
};

//! The points where a connected piece of `mesh` touches itself: two of its
//! vertices at the same exact point. That happens where the solid surface
//! touches a face of the region from inside (at a vertex, or along an edge
//! lying in the face): the solid there is not a 2-manifold (its thickness
//! drops to zero), and split_soup() or CGAL can only give the point one
//! vertex per umbrella, so the block would touch itself. Sorted, unique.
std::vector<ExactPoint> pinch_points(ExactMesh& mesh) {
  std::vector<ExactPoint> out;
  if (mesh.number_of_faces() == 0) return out;
  auto fcc = mesh.add_property_map<FaceIndex, std::size_t>("f:pinch_cc", 0).first;
  PMP::connected_components(mesh, fcc);
  std::map<ExactPoint, std::vector<std::size_t>, ExactPointLess> components_at;
  for (VertexIndex v : mesh.vertices()) {
    if (mesh.is_isolated(v)) continue;
    HalfedgeIndex h = mesh.halfedge(v);
    if (mesh.is_border(h)) h = mesh.opposite(h);
    std::vector<std::size_t>& at = components_at[mesh.point(v)];
    const std::size_t c = fcc[mesh.face(h)];
    if (std::find(at.begin(), at.end(), c) != at.end())
      out.push_back(mesh.point(v));
    else
      at.push_back(c);
  }
  mesh.remove_property_map(fcc);
  std::sort(out.begin(), out.end(), ExactPointLess());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

//! The contact at pinch point p of `mesh`: p and the far ends of the edges
//! that the umbrellas at p share geometrically (two vertices at p joined to
//! two vertices at one point q: the surface touches the region along the
//! segment pq). Sorted, unique, p included.
std::vector<ExactPoint> contact_points(const ExactMesh& mesh, const ExactPoint& p) {
  std::map<ExactPoint, std::vector<VertexIndex>, ExactPointLess> ends;  // far end -> vertices at p
  for (VertexIndex v : mesh.vertices()) {
    if (mesh.is_isolated(v) || mesh.point(v) != p) continue;
    for (HalfedgeIndex h : CGAL::halfedges_around_target(mesh.halfedge(v), mesh)) {
      auto& at = ends[mesh.point(mesh.source(h))];
      if (std::find(at.begin(), at.end(), v) == at.end()) at.push_back(v);
    }
  }
  std::vector<ExactPoint> out{p};
  for (const auto& [q, at] : ends)
    if (at.size() > 1) out.push_back(q);
  return out;
}

//! Is p on the face of `b` in plane x_k = b.min[k] or b.max[k] (closed)?
bool on_box_face(const ExactPoint& p, const Box3& b, int k) {
  if (p[k] != FT(b.min[k]) && p[k] != FT(b.max[k])) return false;
  for (int j = 0; j < 3; ++j)
    if (j != k && (p[j] < FT(b.min[j]) || p[j] > FT(b.max[j]))) return false;
  return true;
}

//! Adds, for each pinch point, one plane through it to `cuts`: the first
//! axis along which the point has a double coordinate strictly inside `box`,
//! not cut yet, and the point lies on no face of a hole across that axis (a
//! plane across the region faces the surface touches splits the
//! zero-thickness point between two blocks, each a 2-manifold there).
//! Returns false when no point got one.
bool add_pinch_cuts(const std::vector<ExactPoint>& pinches, const Box3& box, const std::vector<Box3>& holes,
                    Cuts& cuts, std::size_t& num_added) {
  bool added = false;
  for (const ExactPoint& p : pinches)
    for (int k = 0; k < 3; ++k) {
      const double v = CGAL::to_double(CGAL::exact(p[k]));
      if (FT(v) != p[k] || !(v > box.min[k] && v < box.max[k]) || is_cut(cuts, k, v)) continue;
      if (std::any_of(holes.begin(), holes.end(), [&](const Box3& h) { return on_box_face(p, h, k); })) continue;
      auto& c = cuts[static_cast<std::size_t>(k)];
      c.insert(std::upper_bound(c.begin(), c.end(), v), v);
      added = true;
      ++num_added;
      break;
    }
  return added;
}

//! The connected components of `mesh`, each its own mesh.
std::vector<ExactMesh> split_components(const ExactMesh& mesh) {
  std::vector<ExactMesh> out;
  PMP::split_connected_components(mesh, out);
  return out;
}

//! How carve_region() ended.
enum class RegionStatus {
  kDone,         // `out` holds the pieces
  kNotManifold,  // a difference would not be a 2-manifold
  kPinched,      // a piece touches itself before a hole was subtracted: cut through `pinches` first
};

//! solid ∩ (box \ ∪ holes) as exact pieces, each box of the grid that
//! `cuts` make of `box` on its own: clipped, then the holes overlapping it
//! subtracted. CGAL's corefinement requires meshes that do not
//! self-intersect (CGAL 5.5 segfaulted in corefine_and_compute_difference
//! on a clipped piece of couplingdown.off that touched itself): a piece
//! whose components touch each other is split into its components first;
//! one that touches itself stops the carve (kPinched, with the points).
RegionStatus carve_region(const Mesh& solid, const detail::SolidIndex& index, const Box3& box,
                          const std::vector<Box3>& holes, const Cuts& cuts, std::vector<ExactMesh>& out,
                          std::vector<ExactPoint>& pinches) {
  for (const Box3& cell : region_cells(box, {}, cuts))
    for (ExactMesh& clipped : clip_to_box(solid, index, cell)) {
      std::vector<ExactMesh> work;
      work.push_back(std::move(clipped));
      for (const Box3& h : holes) {
        if (!h.overlaps(cell)) continue;
        std::vector<ExactMesh> next;
        for (ExactMesh& piece : work) {
          if (piece.number_of_faces() == 0) continue;
          std::vector<ExactMesh> parts;
          if (detail::has_coincident_vertices(piece)) {
            pinches = pinch_points(piece);
            if (!pinches.empty()) return RegionStatus::kPinched;
            parts = split_components(piece);
          } else {
            parts.push_back(std::move(piece));
          }
          for (ExactMesh& part : parts) {
            ExactMesh cutter = detail::box_mesh(h);
            ExactMesh result;
            if (!PMP::corefine_and_compute_difference(part, cutter, result)) return RegionStatus::kNotManifold;
            next.push_back(std::move(result));
          }
        }
        work = std::move(next);
      }
      for (ExactMesh& piece : work)
        if (piece.number_of_faces() > 0) out.push_back(std::move(piece));
    }
  return RegionStatus::kDone;
}

//! Splits `mesh` into connected pieces and keeps those touching the input surface.
void collect_pieces(ExactMesh& mesh, const Mesh& solid, const detail::SolidIndex& index, const PlaneSet& planes,
                    BoxPieces& out) {
  if (mesh.number_of_faces() == 0) return;
  auto fcc = mesh.add_property_map<ExactMesh::Face_index, std::size_t>("f:cc", 0).first;
  const std::size_t num_cc = PMP::connected_components(mesh, fcc);
  // Which components touch the input surface.
  std::vector<char> touches(num_cc, 0);
  std::vector<std::vector<ExactMesh::Face_index>> on_planes(num_cc);
  for (auto f : mesh.faces()) {
    const std::size_t c = fcc[f];
    if (touches[c]) continue;
    auto h = mesh.halfedge(f);
    const ExactPoint& a = mesh.point(mesh.source(h));
    const ExactPoint& b = mesh.point(mesh.target(h));
    const ExactPoint& d = mesh.point(mesh.target(mesh.next(h)));
    if (!planes.holds(a, b, d))
      touches[c] = 1;  // not a cut face: a piece of the input surface
    else
      on_planes[c].push_back(f);
  }
  for (std::size_t c = 0; c < num_cc; ++c) {
    if (touches[c]) continue;
    for (auto f : on_planes[c]) {
      auto h = mesh.halfedge(f);
      const ExactPoint centroid = CGAL::centroid(mesh.point(mesh.source(h)), mesh.point(mesh.target(h)),
                                                 mesh.point(mesh.target(mesh.next(h))));
      if (on_input_surface(solid, index, centroid)) {
        touches[c] = 1;
        break;
      }
    }
  }
  // The kept pieces outlive the arena: build them on the normal heap.
  detail::SuspendArena heap;
  const Mesh all = detail::to_double(mesh, &out.rounding);
  // Face order of `all` follows mesh.faces(); split by component.
  std::vector<Mesh> pieces(num_cc);
  std::vector<std::vector<int>> remap(num_cc);
  std::size_t fi = 0;
  for (auto f : mesh.faces()) {
    const std::size_t c = fcc[f];
    const Triangle& t = all.faces[fi++];
    if (!touches[c]) continue;
    auto& map = remap[c];
    if (map.empty()) map.assign(all.num_vertices(), -1);
    Triangle nt{};
    for (int k = 0; k < 3; ++k) {
      int& m = map[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
      if (m < 0) {
        m = static_cast<int>(pieces[c].vertices.size());
        pieces[c].vertices.push_back(all.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])]);
      }
      nt[static_cast<std::size_t>(k)] = m;
    }
    pieces[c].faces.push_back(nt);
  }
  for (std::size_t c = 0; c < num_cc; ++c) {
    if (touches[c])
      out.pieces.push_back(std::move(pieces[c]));
    else
      ++out.num_dropped;
  }
}

void carve_in_arena(const Mesh& solid, const detail::SolidIndex& index, const std::vector<HeightBox>& boxes,
                    std::size_t i, BoxPieces& out) {
  const Box3& box = boxes[i].box;
  std::vector<Box3> holes;
  std::vector<std::size_t> hole_ids;
  for (std::size_t j = 0; j < i; ++j) {
    const Box3& other = boxes[j].box;
    if (!other.overlaps(box)) continue;
    if (other.contains(box.min) && other.contains(box.max)) return;  // fully taken
    holes.push_back(other);
    hole_ids.push_back(j);
  }
  // Carve the region; where a piece touches itself (pinch_points), cut the
  // region through the pinch and carve again (a cut plane may touch the
  // surface elsewhere: then that contact is cut in the next round; a contact
  // on a region edge may need a second plane).
  constexpr int kMaxPinchRounds = 8;
  Cuts cuts;
  std::vector<ExactMesh> pieces;
  for (int round = 0;; ++round) {
    pieces.clear();
    std::vector<ExactPoint> pinched;
    const RegionStatus status = carve_region(solid, index, box, holes, cuts, pieces, pinched);
    if (status == RegionStatus::kPinched && round < kMaxPinchRounds &&
        add_pinch_cuts(pinched, box, holes, cuts, out.num_pinch_cuts))
      continue;  // cut through the contact before subtracting the holes
    out.split_region = status != RegionStatus::kDone;
    if (out.split_region) {
      // A difference would not be a 2-manifold: cut the region into disjoint
      // boxes and clip each one (clip_to_box splits non-manifold results).
      pieces.clear();
      for (const Box3& cell : region_cells(box, holes, cuts))
        for (ExactMesh& part : clip_to_box(solid, index, cell)) pieces.push_back(std::move(part));
    }
    std::vector<ExactPoint> pinches;
    for (ExactMesh& piece : pieces)
      for (const ExactPoint& p : pinch_points(piece)) pinches.push_back(p);
    if (pinches.empty()) break;
    std::sort(pinches.begin(), pinches.end(), ExactPointLess());
    if (round == kMaxPinchRounds || !add_pinch_cuts(pinches, box, holes, cuts, out.num_pinch_cuts)) {
      // No axis-aligned plane through the contacts left to try: keep the
      // pieces and report the region faces that hold each contact
      // (carve_blocks() moves one of them off the contact and carves again).
      out.num_unresolved_pinches = pinches.size();
      for (ExactMesh& piece : pieces)
        for (const ExactPoint& p : pinch_points(piece)) {
          const std::vector<ExactPoint> contact = contact_points(piece, p);
          std::vector<BoxFace> faces;
          auto add_faces = [&](const Box3& b, std::size_t id) {
            for (int k = 0; k < 3; ++k)
              for (int side : {-1, 1}) {
                const FT plane(side < 0 ? b.min[k] : b.max[k]);
                if (std::all_of(contact.begin(), contact.end(),
                                [&](const ExactPoint& q) { return q[k] == plane && on_box_face(q, b, k); }))
                  faces.push_back({id, k, side});
              }
          };
          add_faces(box, i);
          for (std::size_t h = 0; h < holes.size(); ++h) add_faces(holes[h], hole_ids[h]);
          detail::SuspendArena heap;  // the report outlives the arena
          out.contacts.push_back(Contact{std::vector<BoxFace>(faces.begin(), faces.end())});
        }
      break;
    }
  }
  PlaneSet planes;
  planes.add(box);
  for (const Box3& h : holes) planes.add(h);
  for (int k = 0; k < 3; ++k)
    for (double v : cuts[static_cast<std::size_t>(k)]) planes.add(k, v);
  planes.finish();
  for (ExactMesh& piece : pieces) collect_pieces(piece, solid, index, planes, out);
}

//! The pieces of box i, computed in a private arena (see deterministic_arena.h)
//! so that the result does not depend on the thread that runs it.
BoxPieces carve_one(const Mesh& solid, const detail::SolidIndex& index, const std::vector<HeightBox>& boxes,
                    std::size_t i) {
  BoxPieces out;
  std::string error;
  detail::warm_up_exact_booleans();
  {
    detail::DeterministicArena arena;
    try {
      carve_in_arena(solid, index, boxes, i, out);
    } catch (const std::exception& e) {
      detail::SuspendArena heap;
      error = e.what();
    }
  }
  if (!error.empty()) throw AlgorithmError("carving box " + std::to_string(i) + ": " + error);
  return out;
}

//! Moves box faces off the contacts that no axis-aligned cut separated
//! (carve_blocks()). The region of a box is bounded by its own faces and by
//! faces of earlier boxes (holes); a contact lies in one of them, with the
//! solid on both sides of that plane (the solid is a 2-manifold: the two
//! pieces that touch there are joined across the plane). Moving that face
//! by a small distance across the contact removes it. A face is moved
//! outward (the box grows: every triangle it held is still held) when the
//! moved box stays exactly valid (SolidIndex::box_is_valid) and within the
//! size limits, else inward (the box shrinks) when every triangle meeting the
//! slab it gives up is still held by some box. Later boxes take the moved box
//! as a hole, so the regions stay disjoint; carve_blocks() takes a move back
//! when a region carved again is no longer a height field. Deterministic:
//! moves are decided in box order.
class ContactMover {
 public:
  ContactMover(const detail::SolidIndex& index, std::vector<HeightBox>& boxes, const CarveOptions& options,
               double diagonal)
      : index_(index), boxes_(boxes), options_(options), step_(options.contact_move * diagonal) {}

  //! Has face f been tried fewer than kMaxMovesPerFace times?
  bool can_try(const BoxFace& f) const {
    auto it = num_tried_.find(f);
    return it == num_tried_.end() || it->second < kMaxMovesPerFace;
  }

  //! The positions face f may move to, at the current step of that face
  //! (x10 each time it is tried again): outward first, when the box stays
  //! valid and within the limits; then inward, when every triangle the box
  //! gives up that way is covered by the shrunk box or another box. Empty
  //! when both are refused. carve_blocks() tries them in turn: an outward
  //! move can break a later box's region where the inward one does not.
  std::vector<Box3> candidates(const BoxFace& f) {
    const HeightBox& hb = boxes_[f.box];
    int& count = num_tried_[f];
    const double step = step_ * std::pow(10.0, count);
    ++count;
    const double at = f.side < 0 ? hb.box.min[f.k] : hb.box.max[f.k];
    std::vector<Box3> out;
    for (int sense : {1, -1}) {
      Box3 moved = hb.box;
      double& c = f.side < 0 ? moved.min[f.k] : moved.max[f.k];
      c = at + sense * f.side * step;
      const bool ok = sense > 0 ? box_fits_limits(moved, hb.axis, options_.max_height, options_.machine_size) &&
                                      index_.box_is_valid(moved, hb.axis)
                                : moved.min[f.k] < moved.max[f.k] && keeps_coverage(f, moved);
      if (ok) out.push_back(moved);
    }
    return out;
  }

  //! Moves box f.box to `moved` (one of candidates(f)) and marks the boxes
  //! whose region changes: the box, and every later box overlapping the old
  //! box or the new one.
  void apply(const BoxFace& f, const Box3& moved, std::vector<char>& dirty) {
    HeightBox& hb = boxes_[f.box];
    Box3 hull = hb.box;
    hull.min = hull.min.cwiseMin(moved.min);
    hull.max = hull.max.cwiseMax(moved.max);
    hb.box = moved;
    ++num_moves_;
    for (std::size_t j = f.box; j < boxes_.size(); ++j)
      if (j == f.box || boxes_[j].box.overlaps(hull)) dirty[j] = 1;
  }

  //! Takes back the last move of face f (the box was `before`); the next
  //! candidates(f) move it further.
  void undo(const BoxFace& f, const HeightBox& before) {
    boxes_[f.box] = before;
    --num_moves_;
  }

  std::size_t num_moves() const { return num_moves_; }

 private:
  //! Box f.box shrunk to `shrunk` across face f: is every triangle that
  //! meets the slab it gives up (closed, exact) still held there by the
  //! shrunk box or another box? Checked on the part of the slab inside the
  //! triangle's bounding box, cell by cell of the other boxes' planes.
  bool keeps_coverage(const BoxFace& f, const Box3& shrunk) const {
    const Box3& old = boxes_[f.box].box;
    Box3 slab = old;
    if (f.side < 0)
      slab.max[f.k] = shrunk.min[f.k];
    else
      slab.min[f.k] = shrunk.max[f.k];
    const Mesh& mesh = index_.mesh();
    for (int face : index_.faces_near_closed_box(slab)) {
      const Triangle& t = mesh.faces[static_cast<std::size_t>(face)];
      const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
      const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
      const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
      if (!detail::triangle_meets_closed_box(a, b, c, slab)) continue;
      Box3 part = slab;
      part.min = part.min.cwiseMax(index_.face_box(face).min);
      part.max = part.max.cwiseMin(index_.face_box(face).max);
      if (!part_is_held(part, a, b, c, f.box, shrunk)) return false;
    }
    return true;
  }

  //! Does the union of the closed boxes (box `skip` replaced by `replacement`)
  //! contain the closed box `part` of the triangle (a, b, c)'s bounding box?
  //! Where the triangle lies in a box plane, that box holds it only when the
  //! triangle's normal leaves the box there (the solid on the box's side).
  bool part_is_held(const Box3& part, const Vec3& a, const Vec3& b, const Vec3& c, std::size_t skip,
                    const Box3& replacement) const {
    auto box_at = [&](std::size_t j) -> const Box3& { return j == skip ? replacement : boxes_[j].box; };
    std::array<std::vector<double>, 3> planes;
    for (int k = 0; k < 3; ++k) {
      auto& p = planes[static_cast<std::size_t>(k)];
      p = {part.min[k], part.max[k]};
      for (std::size_t j = 0; j < boxes_.size(); ++j)
        for (double v : {box_at(j).min[k], box_at(j).max[k]})
          if (v > part.min[k] && v < part.max[k]) p.push_back(v);
      std::sort(p.begin(), p.end());
      p.erase(std::unique(p.begin(), p.end()), p.end());
    }
    // The dimensions the triangle lies flat in, and its normal's sign there.
    std::array<int, 3> flat_sign{};
    for (int k = 0; k < 3; ++k)
      if (a[k] == b[k] && a[k] == c[k]) flat_sign[static_cast<std::size_t>(k)] = detail::normal_component_sign(a, b, c, k);
    auto cell_count = [&](int k) { return std::max<std::size_t>(1, planes[static_cast<std::size_t>(k)].size() - 1); };
    auto coordinate = [&](int k, std::size_t i) {
      const auto& p = planes[static_cast<std::size_t>(k)];
      return p.size() == 1 ? p[0] : 0.5 * (p[i] + p[i + 1]);
    };
    for (std::size_t ix = 0; ix < cell_count(0); ++ix)
      for (std::size_t iy = 0; iy < cell_count(1); ++iy)
        for (std::size_t iz = 0; iz < cell_count(2); ++iz) {
          const Vec3 q(coordinate(0, ix), coordinate(1, iy), coordinate(2, iz));
          bool held = false;
          for (std::size_t j = 0; j < boxes_.size() && !held; ++j) {
            const Box3& h = box_at(j);
            held = (q.array() >= h.min.array()).all() && (q.array() <= h.max.array()).all();
            for (int k = 0; k < 3 && held; ++k) {
              const int s = flat_sign[static_cast<std::size_t>(k)];
              if (q[k] == h.min[k] && s != -1) held = false;
              if (q[k] == h.max[k] && s != 1) held = false;
            }
          }
          if (!held) return false;
        }
    return true;
  }

  static constexpr int kMaxMovesPerFace = 3;
  const detail::SolidIndex& index_;
  std::vector<HeightBox>& boxes_;
  const CarveOptions& options_;
  double step_;
  std::map<BoxFace, int> num_tried_;
  std::size_t num_moves_ = 0;
};

}  // namespace

namespace detail {
void warm_up_exact_booleans() {
  thread_local bool done = false;
  if (done) return;
  done = true;
  SuspendArena heap;  // in case an arena is active on this thread
  auto make = [](double x0, double y0, double z0, double x1, double y1, double z1) {
    return box_mesh(make_box3(Vec3(x0, y0, z0), Vec3(x1, y1, z1)));
  };
  {
    ExactMesh a = make(0, 0, 0, 2, 2, 1), b = make(0.5, 0.5, 0.5, 3, 3, 3), out;
    PMP::clip(a, to_cuboid(make_box3(Vec3(0, 0, 0), Vec3(1.5, 1.5, 1))), CGAL::parameters::clip_volume(true));
    PMP::corefine_and_compute_difference(a, b, out);
  }
  {
    ExactMesh a = make(0, 0, 0, 2, 2, 1), b = make(0.5, 0.5, 0.5, 3, 3, 3), out;
    PMP::corefine_and_compute_union(a, b, out);
    auto fcc = out.add_property_map<ExactMesh::Face_index, std::size_t>("f:cc", 0).first;
    PMP::connected_components(out, fcc);
    RoundingReport r;
    to_double(out, &r);
  }
  {
    ExactMesh a = make(0, 0, 0, 2, 2, 1), b = make(0.5, 0.5, 0.5, 3, 3, 3), out;
    PMP::corefine_and_compute_intersection(a, b, out);
  }
  {
    // A difference whose result is not manifold (two cubes sharing an edge).
    ExactMesh a = make(0, 0, 0, 2, 2, 1), b = make(0, 0, 0, 1, 1, 1), c = make(1, 1, 0, 2, 2, 1), ab, abc;
    if (PMP::corefine_and_compute_difference(a, b, ab)) PMP::corefine_and_compute_difference(ab, c, abc);
  }
  const ExactKernel::Triangle_3 t(ExactPoint(0, 0, 0), ExactPoint(1, 0, 0), ExactPoint(0, 1, 0));
  const ExactPoint c = CGAL::centroid(t[0], t[1], t[2]);
  (void)t.has_on(c);
  (void)(c.x() == FT(0.5));
  (void)CGAL::to_double(CGAL::exact(c.x()));
  ExactKernel::FT zero;
  ExactPoint origin;
  ExactKernel::Vector_3 v;
  ExactKernel::Plane_3 plane;
  ExactKernel::Segment_3 segment;
  ExactKernel::Iso_cuboid_3 cuboid;
  (void)zero;
  (void)origin;
  (void)v;
  (void)plane;
  (void)segment;
  (void)cuboid;
}
}  // namespace detail

CarveResult carve_blocks(const Mesh& solid, const std::vector<HeightBox>& ordered_boxes,
                         const CarveOptions& options) {
  Progress* progress = options.progress;
  if (!(options.contact_move > 0) || options.max_contact_rounds < 0)
    throw InvalidArgumentError("carve_blocks: contact_move must be positive and max_contact_rounds >= 0");
  const detail::SolidIndex index(solid, overhang_sine(options.max_overhang_deg));
  HeightFieldOptions height_field;
  height_field.normal_tolerance = height_field_normal_tolerance(options.max_overhang_deg);
  std::vector<HeightBox> boxes = ordered_boxes;
  std::vector<BoxPieces> per_box(boxes.size());
  std::atomic<std::size_t> done{0};
  parallel_for(0, boxes.size(), [&](std::size_t i) {
    per_box[i] = carve_one(solid, index, boxes, i);
    if (progress) progress->update(++done, boxes.size());
  });

  // Contacts no axis-aligned cut separated: move one region face holding
  // the contact off it, then carve again the boxes whose regions changed.
  // A move also changes the regions of later boxes (a moved hole face): it
  // is kept only when every piece of every box carved again is still a
  // height field along its box's axis (a later box whose base lay in the
  // moved plane would get faces one step above its base: anchor.off), and
  // taken back otherwise.
  ContactMover mover(index, boxes, options, bounding_box(solid).diagonal());
  auto all_height_fields = [&](const std::vector<std::size_t>& ids, const std::vector<BoxPieces>& pieces) {
    for (std::size_t n = 0; n < ids.size(); ++n)
      for (const Mesh& m : pieces[n].pieces)
        if (!is_height_field(m, axis_direction(boxes[ids[n]].axis), height_field)) return false;
    return true;
  };
  for (int round = 0; round < options.max_contact_rounds; ++round) {
    bool moved_any = false;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const std::vector<Contact> contacts = per_box[i].contacts;
      bool recarved_i = false;
      for (const Contact& c : contacts) {
        if (recarved_i) break;  // a move this round already changed the region
        for (const BoxFace& f : c.faces) {
          // Outward, then inward, at growing steps, until a move is kept.
          const HeightBox before = boxes[f.box];
          bool kept = false;
          while (!kept && mover.can_try(f)) {
            for (const Box3& moved : mover.candidates(f)) {
              std::vector<char> dirty(boxes.size(), 0);
              mover.apply(f, moved, dirty);
              std::vector<std::size_t> again;
              for (std::size_t j = 0; j < boxes.size(); ++j)
                if (dirty[j]) again.push_back(j);
              std::vector<BoxPieces> redone(again.size());
              parallel_for(0, again.size(),
                           [&](std::size_t n) { redone[n] = carve_one(solid, index, boxes, again[n]); });
              if (!all_height_fields(again, redone)) {
                mover.undo(f, before);
                continue;
              }
              for (std::size_t n = 0; n < again.size(); ++n) {
                per_box[again[n]] = std::move(redone[n]);
                recarved_i = recarved_i || again[n] == i;
              }
              kept = true;
              break;
            }
          }
          if (!kept) continue;
          moved_any = true;
          break;
        }
      }
    }
    if (!moved_any) break;
  }

  CarveResult result;
  result.num_moved_faces = mover.num_moves();
  for (std::size_t i = 0; i < per_box.size(); ++i) {
    BoxPieces& p = per_box[i];
    result.num_dropped_pieces += p.num_dropped;
    result.num_split_regions += p.split_region ? 1 : 0;
    result.num_pinched_regions += p.num_pinch_cuts > 0 ? 1 : 0;
    result.num_pinch_cuts += p.num_pinch_cuts;
    result.num_unresolved_pinches += p.num_unresolved_pinches;
    result.num_degenerate_faces += p.rounding.num_degenerate_faces;
    result.num_flipped_faces += p.rounding.num_flipped_faces;
    for (Mesh& m : p.pieces)
      result.blocks.push_back(Block{std::move(m), boxes[i].axis, static_cast<int>(i)});
  }
  if (progress) {
    progress->info(std::to_string(result.blocks.size()) + " blocks carved from " +
                   std::to_string(ordered_boxes.size()) + " boxes (" + std::to_string(result.num_dropped_pieces) +
                   " interior pieces dropped)");
    if (result.num_split_regions > 0)
      progress->warn(std::to_string(result.num_split_regions) +
                     " box regions were not manifold and were cut into disjoint boxes");
    if (result.num_pinched_regions > 0)
      progress->info(std::to_string(result.num_pinched_regions) +
                     " box regions touched by the surface from inside were cut through the contact (" +
                     std::to_string(result.num_pinch_cuts) + " planes)");
    if (result.num_moved_faces > 0)
      progress->info(std::to_string(result.num_moved_faces) +
                     " box faces moved off contacts no axis-aligned cut could separate");
    if (result.num_unresolved_pinches > 0)
      progress->warn(std::to_string(result.num_unresolved_pinches) +
                     " points where the surface touches a box region from inside could not be cut apart: the "
                     "blocks there touch themselves");
    if (result.num_degenerate_faces + result.num_flipped_faces > 0)
      progress->warn("rounding the exact blocks to doubles made " + std::to_string(result.num_degenerate_faces) +
                     " faces degenerate and flipped " + std::to_string(result.num_flipped_faces));
  }
  return result;
}

}  // namespace subfab
