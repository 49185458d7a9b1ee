// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/carve_blocks.h"

#include <CGAL/Polygon_mesh_processing/clip.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <exception>
#include <string>
#include <vector>

#include "decompose/deterministic_arena.h"
#include "decompose/exact_mesh.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

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
bool on_input_surface(const Mesh& solid, const ExactPoint& p) {
  const Vec3 q(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  for (const Triangle& t : solid.faces) {
    const Vec3& a = solid.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = solid.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = solid.vertices[static_cast<std::size_t>(t[2])];
    const Vec3 lo = a.cwiseMin(b).cwiseMin(c);
    const Vec3 hi = a.cwiseMax(b).cwiseMax(c);
    const double slack = 1e-9 * (1.0 + (hi - lo).norm() + q.cwiseAbs().maxCoeff());
    if ((q.array() < lo.array() - slack).any() || (q.array() > hi.array() + slack).any()) continue;
    const ExactKernel::Triangle_3 tri(ExactPoint(a.x(), a.y(), a.z()), ExactPoint(b.x(), b.y(), b.z()),
                                      ExactPoint(c.x(), c.y(), c.z()));
    if (!tri.is_degenerate() && tri.has_on(p)) return true;
  }
  return false;
}

//! Cuts region = box \ (union of `holes`) into disjoint boxes (grid cells of
//! the hole planes, merged into runs along x then y).
std::vector<Box3> region_cells(const Box3& box, const std::vector<Box3>& holes) {
  std::array<std::vector<double>, 3> planes;
  for (int k = 0; k < 3; ++k) {
    auto& p = planes[static_cast<std::size_t>(k)];
    p = {box.min[k], box.max[k]};
    for (const Box3& h : holes)
      for (double v : {h.min[k], h.max[k]})
        if (v > box.min[k] && v < box.max[k]) p.push_back(v);
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
        while (e < nx && is_free(e)) ++e;
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
          m.max.z() == r.max.z() && m.max.y() == r.min.y()) {
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

//! solid ∩ box, exactly; false when the result would not be manifold.
bool clip_to_box(ExactMesh& mesh, const Box3& box) {
  return PMP::clip(mesh, to_cuboid(box), CGAL::parameters::clip_volume(true));
}

//! The per-box work product.
struct BoxPieces {
  std::vector<Mesh> pieces;
  std::size_t num_dropped = 0;
  bool split_region = false;
  detail::RoundingReport rounding;
};

//! Splits `mesh` into connected pieces and keeps those touching the input surface.
void collect_pieces(ExactMesh& mesh, const Mesh& solid, const PlaneSet& planes, BoxPieces& out) {
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
      if (on_input_surface(solid, centroid)) {
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

void carve_in_arena(const Mesh& solid, const std::vector<HeightBox>& boxes, std::size_t i, BoxPieces& out) {
  const Box3& box = boxes[i].box;
  std::vector<Box3> holes;
  PlaneSet planes;
  planes.add(box);
  for (std::size_t j = 0; j < i; ++j) {
    const Box3& other = boxes[j].box;
    if (!other.overlaps(box)) continue;
    if (other.contains(box.min) && other.contains(box.max)) return;  // fully taken
    holes.push_back(other);
    planes.add(other);
  }
  planes.finish();

  ExactMesh piece = detail::to_exact(solid);
  bool manifold = clip_to_box(piece, box);
  if (manifold) {
    for (const Box3& h : holes) {
      if (piece.number_of_faces() == 0) break;
      ExactMesh cutter = detail::box_mesh(h);
      ExactMesh result;
      if (!PMP::corefine_and_compute_difference(piece, cutter, result)) {
        manifold = false;
        break;
      }
      piece = std::move(result);
    }
  }
  if (manifold) {
    collect_pieces(piece, solid, planes, out);
    return;
  }
  // Fallback: cut the region into disjoint boxes and clip each one.
  out.split_region = true;
  for (const Box3& cell : region_cells(box, holes)) {
    ExactMesh part = detail::to_exact(solid);
    if (!clip_to_box(part, cell))
      throw AlgorithmError("the solid inside a region cell is not a 2-manifold (it touches the cell "
                           "along an edge or a vertex); try a different --grid-factor");
    collect_pieces(part, solid, planes, out);
  }
}

//! The pieces of box i, computed in a private arena (see deterministic_arena.h)
//! so that the result does not depend on the thread that runs it.
BoxPieces carve_one(const Mesh& solid, const std::vector<HeightBox>& boxes, std::size_t i) {
  BoxPieces out;
  std::string error;
  detail::warm_up_exact_booleans();
  {
    detail::DeterministicArena arena;
    try {
      carve_in_arena(solid, boxes, i, out);
    } catch (const std::exception& e) {
      detail::SuspendArena heap;
      error = e.what();
    }
  }
  if (!error.empty()) throw AlgorithmError("carving box " + std::to_string(i) + ": " + error);
  return out;
}

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
  std::vector<BoxPieces> per_box(ordered_boxes.size());
  std::atomic<std::size_t> done{0};
  parallel_for(0, ordered_boxes.size(), [&](std::size_t i) {
    per_box[i] = carve_one(solid, ordered_boxes, i);
    if (progress) progress->update(++done, ordered_boxes.size());
  });

  CarveResult result;
  for (std::size_t i = 0; i < per_box.size(); ++i) {
    BoxPieces& p = per_box[i];
    result.num_dropped_pieces += p.num_dropped;
    result.num_split_regions += p.split_region ? 1 : 0;
    result.num_degenerate_faces += p.rounding.num_degenerate_faces;
    result.num_flipped_faces += p.rounding.num_flipped_faces;
    for (Mesh& m : p.pieces)
      result.blocks.push_back(Block{std::move(m), ordered_boxes[i].axis, static_cast<int>(i)});
  }
  if (progress) {
    progress->info(std::to_string(result.blocks.size()) + " blocks carved from " +
                   std::to_string(ordered_boxes.size()) + " boxes (" + std::to_string(result.num_dropped_pieces) +
                   " interior pieces dropped)");
    if (result.num_split_regions > 0)
      progress->warn(std::to_string(result.num_split_regions) +
                     " box regions were not manifold and were cut into disjoint boxes");
    if (result.num_degenerate_faces + result.num_flipped_faces > 0)
      progress->warn("rounding the exact blocks to doubles made " + std::to_string(result.num_degenerate_faces) +
                     " faces degenerate and flipped " + std::to_string(result.num_flipped_faces));
  }
  return result;
}

}  // namespace subfab
