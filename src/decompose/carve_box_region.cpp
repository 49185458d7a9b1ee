// SPDX-License-Identifier: GPL-3.0-or-later
// Carving one box's region (thesis Section 4.3.3): clip the solid to the
// grid cells of the region's cuts, subtract the holes, cut through pinch
// points and carve again, keep the pieces touching the input surface; see
// carve_box_region.h.
#include "decompose/carve_box_region.h"

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/repair.h>

#include <algorithm>
#include <array>
#include <exception>
#include <string>
#include <utility>

#include "decompose/pinch_points.h"
#include "geometry/clip_solid_to_box.h"
#include "geometry/deterministic_arena.h"
#include "subfab/core/error.h"

namespace subfab::detail {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
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
//! on a clipped piece of couplingdown.off that touched itself, and looped
//! for ever on a piece of rotor.off with a pinched vertex, left by the
//! previous hole's difference): pinched vertices are split, then a piece
//! whose components touch each other is split into its components; one
//! that touches itself stops the carve (kPinched, with the points).
RegionStatus carve_region(const Mesh& solid, const detail::SolidIndex& index, const Box3& box,
                          const std::vector<Box3>& holes, const Cuts& cuts, std::vector<ExactMesh>& out,
                          std::vector<ExactPoint>& pinches) {
  for (const Box3& cell : region_cells(box, {}, cuts))
    for (ExactMesh& clipped : clip_solid_to_box(solid, index, cell)) {
      std::vector<ExactMesh> work;
      work.push_back(std::move(clipped));
      for (const Box3& h : holes) {
        if (!h.overlaps(cell)) continue;
        std::vector<ExactMesh> next;
        for (ExactMesh& piece : work) {
          if (piece.number_of_faces() == 0) continue;
          std::vector<ExactMesh> parts;
          PMP::duplicate_non_manifold_vertices(piece);  // else CGAL's difference may never return
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
      // boxes and clip each one (clip_solid_to_box splits non-manifold results).
      pieces.clear();
      for (const Box3& cell : region_cells(box, holes, cuts))
        for (ExactMesh& part : clip_solid_to_box(solid, index, cell)) pieces.push_back(std::move(part));
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

}  // namespace

BoxPieces carve_box_region(const Mesh& solid, const SolidIndex& index, const std::vector<HeightBox>& boxes,
                           std::size_t i) {
  BoxPieces out;
  detail::warm_up_exact_booleans();
  const std::string error = detail::run_in_arena([&] { carve_in_arena(solid, index, boxes, i, out); });
  if (!error.empty()) throw AlgorithmError("carving box " + std::to_string(i) + ": " + error);
  return out;
}

}  // namespace subfab::detail
