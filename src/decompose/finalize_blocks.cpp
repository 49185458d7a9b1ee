// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/finalize_blocks.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <memory>
#include <utility>
#include <string>
#include <unordered_map>
#include <vector>

#include "geometry/exact_mesh.h"
#include "geometry/rotate_accurately.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/validate/block_name.h"
#include "subfab/validate/validate_decomposition.h"

namespace subfab {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using VertexIndex = SurfaceMesh::Vertex_index;
using HalfedgeIndex = SurfaceMesh::Halfedge_index;
using EdgeIndex = SurfaceMesh::Edge_index;
using FaceIndex = SurfaceMesh::Face_index;

Vec3 vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }

SurfaceMesh to_block_surface_mesh(const Mesh& block) {
  return detail::to_surface_mesh<SurfaceMesh>(
      block, " of a block cannot be added to a halfedge mesh (non-manifold or inconsistently oriented)");
}

//! Back to a plain mesh: surviving vertices in index order, unused ones dropped.
Mesh to_mesh(const SurfaceMesh& sm) {
  Mesh out;
  std::vector<int> index(sm.num_vertices(), -1);
  for (VertexIndex v : sm.vertices()) {
    if (sm.is_isolated(v)) continue;
    index[v.idx()] = static_cast<int>(out.vertices.size());
    out.vertices.push_back(vec(sm.point(v)));
  }
  for (FaceIndex f : sm.faces()) {
    Triangle t{};
    HalfedgeIndex h = sm.halfedge(f);
    for (std::size_t k = 0; k < 3; ++k, h = sm.next(h)) t[k] = index[sm.target(h).idx()];
    out.faces.push_back(t);
  }
  return out;
}

//! The one cleanup of rounding artefacts on one block (see clean_rounded_block()).
class Cleaner {
 public:
  Cleaner(SurfaceMesh& sm, const Vec3& direction, double tolerance)
      : sm_(sm), direction_(direction), tol2_(tolerance * tolerance), tol_(tolerance) {}

  //! Collapses every edge shorter than the tolerance that can be collapsed.
  std::size_t collapse_short_edges() {
    std::size_t n = 0;
    for (SurfaceMesh::size_type i = 0; i < sm_.num_edges(); ++i) {
      const EdgeIndex e(i);
      if (sm_.is_removed(e) || sm_.number_of_vertices() <= 4) continue;
      const HalfedgeIndex h = sm_.halfedge(e);
      const VertexIndex a = sm_.source(h), b = sm_.target(h);
      if (CGAL::squared_distance(sm_.point(a), sm_.point(b)) >= tol2_) continue;
      if (!CGAL::Euler::does_satisfy_link_condition(e, sm_)) continue;
      // Keep the endpoint lower along the direction (base faces stay on the base); ties: lower index.
      const double da = vec(sm_.point(a)).dot(direction_), db = vec(sm_.point(b)).dot(direction_);
      const Point kept = (da < db || (da == db && a < b)) ? sm_.point(a) : sm_.point(b);
      const VertexIndex v = CGAL::Euler::collapse_edge(e, sm_);
      sm_.point(v) = kept;
      ++n;
    }
    return n;
  }

  //! Flips the longest edge of every face whose opposite corner lies closer
  //! than the tolerance to it (a cap), when the flip is valid.
  std::size_t flip_caps() {
    std::size_t n = 0;
    for (SurfaceMesh::size_type i = 0; i < sm_.num_faces(); ++i) {
      const FaceIndex f(i);
      if (sm_.is_removed(f)) continue;
      // The longest edge h (a -> b) and the corner v opposite it.
      HalfedgeIndex h = sm_.halfedge(f), best = h;
      double longest = -1.0;
      for (int k = 0; k < 3; ++k, h = sm_.next(h)) {
        const double l = CGAL::squared_distance(sm_.point(sm_.source(h)), sm_.point(sm_.target(h)));
        if (l > longest) {
          longest = l;
          best = h;
        }
      }
      const Vec3 a = vec(sm_.point(sm_.source(best))), b = vec(sm_.point(sm_.target(best)));
      const Vec3 v = vec(sm_.point(sm_.target(sm_.next(best))));
      const double ab = (b - a).norm();
      if (!(ab > 0.0) || (b - a).cross(v - a).norm() / ab >= tol_) continue;
      if (try_flip(best)) ++n;
    }
    return n;
  }

 private:
  //! Flips h (face a b v, opposite face b a w) into (a w v), (w b v) when
  //! that is a valid, better triangulation of the quad.
  bool try_flip(HalfedgeIndex h) {
    const HalfedgeIndex o = sm_.opposite(h);
    if (sm_.is_border(h) || sm_.is_border(o)) return false;
    const VertexIndex va = sm_.source(h), vb = sm_.target(h);
    const VertexIndex vv = sm_.target(sm_.next(h)), vw = sm_.target(sm_.next(o));
    if (vv == vw || CGAL::halfedge(vv, vw, sm_).second) return false;  // would make a non-manifold edge
    if (sm_.degree(va) <= 3 || sm_.degree(vb) <= 3) return false;      // would leave a vertex of degree 2
    const Vec3 a = vec(sm_.point(va)), b = vec(sm_.point(vb)), v = vec(sm_.point(vv)), w = vec(sm_.point(vw));
    // The opposite face must be a proper triangle, and the two new faces
    // must keep its orientation and be less thin than the cap.
    const Vec3 n2 = (a - b).cross(w - b);
    const Vec3 n3 = (w - a).cross(v - a), n4 = (b - w).cross(v - w);
    if (n2.squaredNorm() == 0.0 || n3.dot(n2) <= 0.0 || n4.dot(n2) <= 0.0) return false;
    auto min_height = [](const Vec3& p, const Vec3& q, const Vec3& r) {
      const double area2 = (q - p).cross(r - p).norm();
      const double longest = std::max({(q - p).norm(), (r - q).norm(), (p - r).norm()});
      return longest > 0.0 ? area2 / longest : 0.0;
    };
    const double before = std::min(min_height(a, b, v), min_height(b, a, w));
    const double after = std::min(min_height(a, w, v), min_height(w, b, v));
    if (!(after > before)) return false;
    CGAL::Euler::flip_edge(h, sm_);
    return true;
  }

  SurfaceMesh& sm_;
  Vec3 direction_;
  double tol2_;
  double tol_;
};

struct VecHash {
  std::size_t operator()(const Vec3& v) const {
    std::size_t h = 0;
    for (int k = 0; k < 3; ++k) h = h * 1000003u ^ std::hash<double>()(v[k]);
    return h;
  }
};

//! The work product of one block.
struct Finished {
  FinalBlock block;
  CleanupReport cleanup;
  bool dropped = false;
  std::string error;
};

}  // namespace

Mesh frame_twin(const Mesh& finished, const Mesh& rounded, const std::vector<Vec3>& frame,
                const Eigen::Matrix3d& rotation) {
  // rounded point -> the least frame point rounded to it
  std::unordered_map<Vec3, Vec3, VecHash> source;
  const auto less = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  const std::size_t n = std::min(rounded.num_vertices(), frame.size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto [it, added] = source.emplace(rounded.vertices[i], frame[i]);
    if (!added && less(frame[i], it->second)) it->second = frame[i];
  }
  Mesh twin;
  twin.faces = finished.faces;
  twin.vertices.reserve(finished.num_vertices());
  for (const Vec3& v : finished.vertices) {
    const auto it = source.find(v);
    twin.vertices.push_back(it != source.end() ? it->second : detail::rotate_accurately(rotation, v));
  }
  return twin;
}

CleanupReport clean_rounded_block(Mesh& block, const Vec3& direction, double tolerance,
                                  const FinalizeOptions& options) {
  CleanupReport report;
  SurfaceMesh sm = to_block_surface_mesh(block);
  Cleaner cleaner(sm, direction, tolerance);
  for (int pass = 0; pass < options.max_passes; ++pass) {
    const std::size_t collapsed = cleaner.collapse_short_edges();
    const std::size_t flipped = cleaner.flip_caps();
    report.num_collapsed_edges += collapsed;
    report.num_flipped_edges += flipped;
    if (collapsed + flipped == 0) break;
  }
  if (sm.number_of_faces() <= 4 && report.num_collapsed_edges > 0) {
    // Collapsed to (at most) a tetrahedron thinner than the tolerance: nothing is left.
    bool thin = true;
    for (FaceIndex f : sm.faces()) {
      HalfedgeIndex h = sm.halfedge(f);
      const Vec3 a = vec(sm.point(sm.source(h))), b = vec(sm.point(sm.target(h)));
      const Vec3 c = vec(sm.point(sm.target(sm.next(h))));
      const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
      if (longest > 0 && (b - a).cross(c - a).norm() / longest >= tolerance) thin = false;
    }
    if (thin) sm.clear();
  }
  block = to_mesh(sm);
  return report;
}

std::optional<double> clean_to_closed_solid(Mesh& block, const Vec3& direction) {
  const FinalizeOptions fo;
  const double tolerance = fo.relative_tolerance * rounding_scale(block);
  try {
    clean_rounded_block(block, direction, tolerance, fo);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (block.faces.empty() || !check_closed_solid(block).ok() || detail::count_degenerate_faces(block) > 0)
    return std::nullopt;
  return tolerance;
}

std::string block_defect(const Mesh& block, const Vec3& direction, double diagonal, const FinalizeOptions& options) {
  const SolidReport solid = check_closed_solid(block);
  if (solid.num_faces == 0) return "it has no faces";
  if (solid.num_boundary_edges + solid.num_non_manifold_edges + solid.num_non_manifold_vertices > 0)
    return "it is not a closed oriented 2-manifold (" + std::to_string(solid.num_boundary_edges) +
           " boundary edges, " + std::to_string(solid.num_non_manifold_edges) + " non-manifold edges, " +
           std::to_string(solid.num_non_manifold_vertices) + " non-manifold vertices)";
  if (const std::size_t n = detail::count_degenerate_faces(block))
    return "it has " + std::to_string(n) + " zero-area faces";
  if (!(solid.volume > 0.0)) return "its volume is not positive (" + std::to_string(solid.volume) + ")";
  HeightFieldOptions ho;
  ho.normal_tolerance = options.normal_tolerance;
  ho.plane_tolerance = 1e-9 * std::max(1.0, diagonal);
  const HeightFieldReport hf = check_height_field(block, direction, ho);
  if (!hf.ok()) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%zu faces off the base face away from the milling direction (worst cosine %.4f)",
                  hf.num_overhang_faces, hf.worst_cosine);
    return buf;
  }
  const SurfaceMesh sm = to_block_surface_mesh(block);
  if (PMP::does_self_intersect(sm)) {
    std::vector<std::pair<FaceIndex, FaceIndex>> pairs;
    PMP::self_intersections(sm, std::back_inserter(pairs));
    std::string what = "it self-intersects (" + std::to_string(pairs.size()) + " pairs of faces";
    if (!pairs.empty()) {
      auto describe = [&](FaceIndex f) {
        HalfedgeIndex h = sm.halfedge(f);
        const Vec3 a = vec(sm.point(sm.source(h))), b = vec(sm.point(sm.target(h)));
        const Vec3 c = vec(sm.point(sm.target(sm.next(h))));
        const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
        const double shortest = std::min({(b - a).norm(), (c - b).norm(), (a - c).norm()});
        char buf[200];
        std::snprintf(buf, sizeof buf, "face %u [%u %u %u] edges %.3g..%.3g height %.3g",
                      static_cast<unsigned>(f.idx()), static_cast<unsigned>(sm.source(h).idx()),
                      static_cast<unsigned>(sm.target(h).idx()), static_cast<unsigned>(sm.target(sm.next(h)).idx()),
                      shortest, longest, longest > 0 ? (b - a).cross(c - a).norm() / longest : 0.0);
        return std::string(buf);
      };
      what += "; first: " + describe(pairs.front().first) + " and " + describe(pairs.front().second);
    }
    return what + ")";
  }
  return {};
}

//! Steps 1-3 of finalize_blocks() on one block at a time (thread-safe).
struct RoundedBlockCheck::Impl {
  Impl(const Mesh& input_, const DecomposeResult& result, const FinalizeOptions& options_)
      : input(input_), options(options_), back(result.rotation.transpose()), forward(result.rotation) {
    // Canonical input vertices -> input vertices (their exact coordinates come back).
    const std::size_t n_in =
        std::min({result.num_input_vertices, result.canonical.num_vertices(), input.num_vertices()});
    for (std::size_t i = 0; i < n_in; ++i) input_vertex.emplace(result.canonical.vertices[i], static_cast<int>(i));
    diagonal = bounding_box(input).diagonal();
    tolerance = options.relative_tolerance * rounding_scale(input);
  }

  //! \param with_frame also make the block's frame twin (finalize_blocks(), not the checks)
  Finished finish(const Block& b, bool with_frame = false) const {
    Finished out;
    out.block.axis = b.axis;
    out.block.source_box = b.source_box;
    out.block.direction = detail::rotate_accurately(back, axis_direction(b.axis));
    Mesh& m = out.block.mesh;
    m.faces = b.mesh.faces;
    m.vertices.reserve(b.mesh.num_vertices());
    for (const Vec3& c : b.mesh.vertices) {
      auto it = input_vertex.find(c);
      m.vertices.push_back(it != input_vertex.end() ? input.vertices[static_cast<std::size_t>(it->second)]
                                                    : detail::rotate_accurately(back, c));
    }
    const Mesh rounded = m;
    try {
      out.cleanup = clean_rounded_block(m, out.block.direction, tolerance, options);
      if (m.faces.empty()) {
        out.dropped = true;
        return out;
      }
      out.error = block_defect(m, out.block.direction, diagonal, options);
    } catch (const std::exception& e) {
      out.error = e.what();
    }
    // The cleanup's collapses and flips can make a block touch itself
    // (anchor.off: 18 collapses on one block, then 8 pairs of faces
    // crossing); the rounded block as it was is kept when it is valid.
    if (!out.error.empty() && block_defect(rounded, out.block.direction, diagonal, options).empty()) {
      m = rounded;
      out.error.clear();
      out.cleanup = {};
    }
    if (with_frame && out.error.empty()) out.block.frame_mesh = frame_twin(m, rounded, b.mesh.vertices, forward);
    return out;
  }

  const Mesh& input;
  FinalizeOptions options;
  Eigen::Matrix3d back;
  Eigen::Matrix3d forward;
  std::unordered_map<Vec3, int, VecHash> input_vertex;
  double diagonal = 0.0;
  double tolerance = 0.0;
};

RoundedBlockCheck::RoundedBlockCheck(const Mesh& input, const DecomposeResult& result, const FinalizeOptions& options)
    : impl_(std::make_unique<Impl>(input, result, options)) {}

RoundedBlockCheck::~RoundedBlockCheck() = default;

std::string RoundedBlockCheck::defect(const Block& block, Mesh* finished) const {
  Finished f = impl_->finish(block);
  if (finished) *finished = f.dropped ? Mesh{} : std::move(f.block.mesh);
  return f.error;
}

namespace {

//! Steps 1-3 of finalize_blocks() on every block of `result`, in parallel.
//! \param with_frame also make each block's frame twin (finalize_blocks(); the checks need none)
std::vector<Finished> finish_blocks(const Mesh& input, const DecomposeResult& result, const FinalizeOptions& options,
                                    bool with_frame) {
  const RoundedBlockCheck::Impl finisher(input, result, options);
  std::vector<Finished> done(result.blocks.size());
  parallel_for(0, result.blocks.size(), [&](std::size_t i) { done[i] = finisher.finish(result.blocks[i], with_frame); });
  return done;
}

}  // namespace

std::vector<std::string> block_defects_after_rounding(const Mesh& input, const DecomposeResult& result,
                                                      const FinalizeOptions& options) {
  std::vector<Finished> done = finish_blocks(input, result, options, false);
  std::vector<std::string> out;
  out.reserve(done.size());
  for (Finished& f : done) out.push_back(std::move(f.error));
  return out;
}

FinalizeResult finalize_blocks(const Mesh& input, const DecomposeResult& result, const FinalizeOptions& options) {
  std::vector<Finished> done = finish_blocks(input, result, options, true);
  FinalizeResult fr;
  for (std::size_t i = 0; i < done.size(); ++i) {
    Finished& f = done[i];
    if (!f.error.empty())
      throw AlgorithmError(block_name(i) + " (carved from box " + std::to_string(f.block.source_box) +
                           ") is not a valid block after rounding to doubles and cleanup: " + f.error +
                           ". The boxes of this run could not be carved into valid blocks there; another grid "
                           "(--grid-factor 0.8 or 1.25) gives other boxes and may avoid it");
    fr.cleanup.num_collapsed_edges += f.cleanup.num_collapsed_edges;
    fr.cleanup.num_flipped_edges += f.cleanup.num_flipped_edges;
    if (f.dropped) {
      ++fr.num_dropped_blocks;
      continue;
    }
    fr.blocks.push_back(std::move(f.block));
  }
  if (options.progress) {
    if (fr.cleanup.num_collapsed_edges + fr.cleanup.num_flipped_edges > 0)
      options.progress->info("rounding cleanup: " + std::to_string(fr.cleanup.num_collapsed_edges) +
                             " short edges collapsed, " + std::to_string(fr.cleanup.num_flipped_edges) +
                             " cap edges flipped");
    if (fr.num_dropped_blocks > 0)
      options.progress->warn(std::to_string(fr.num_dropped_blocks) +
                             " blocks thinner than the rounding tolerance were dropped");
  }
  return fr;
}

}  // namespace subfab
