// SPDX-License-Identifier: GPL-3.0-or-later
// FillDeviationMeter: the surface deviation that blocks sticking out of a
// solid cause, near one of them (see measure_fill_deviation.h).
#include "subfab/validate/measure_fill_deviation.h"

#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <array>
#include <numeric>
#include <map>
#include <limits>
#include <optional>
#include <utility>

#include "geometry/box_tests.h"
#include "geometry/clip_solid_to_box.h"
#include "geometry/deterministic_arena.h"
#include "geometry/exact_mesh.h"
#include "geometry/solid_index.h"
#include "geometry/surface_deviation.h"
#include "geometry/union_surface.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab {
namespace {

//! The tile holding box b's lowest corner in a grid of square tiles of side
//! `tile` over `all`, in the coordinates i, j (one tile when `tile` is 0).
std::pair<long, long> tile_of(const BoundingBox& b, const BoundingBox& all, int i, int j, double tile) {
  if (!(tile > 0)) return {0, 0};
  return {static_cast<long>(std::floor((b.min[i] - all.min[i]) / tile)),
          static_cast<long>(std::floor((b.min[j] - all.min[j]) / tile))};
}

namespace PMP = CGAL::Polygon_mesh_processing;
using detail::ExactMesh;

BoundingBox widened(BoundingBox box, double margin) {
  box.min.array() -= margin;
  box.max.array() += margin;
  return box;
}

bool inside(const BoundingBox& inner, const BoundingBox& outer) {
  return (outer.min.array() <= inner.min.array()).all() && (inner.max.array() <= outer.max.array()).all();
}

const auto kThrowOnSelfIntersection = CGAL::parameters::throw_on_self_intersection(true);

//! An operand that self-intersects near the cut throws
//! Self_intersection_exception (caught in local_surface(), inside its arena):
//! CGAL 5.5 does not check that precondition otherwise and can crash
//! (decimated_knight.off at --tolerance 5e-4: segfault in a union).
//! The surface of V = (block ∪ others) ∩ region ∪ (solid ∩ region) inside
//! the open region, as a double mesh and the list of its faces that are not
//! on the region's planes. Exact booleans in a deterministic arena.
struct Surface {
  Mesh mesh;
  std::vector<int> faces;     // faces of mesh not on a plane of the region
  std::vector<char> in_inner;  // per entry of `faces`: its three corners lie in the closed inner box (exact)
};

//! Exceptions are caught here, while the arena lives, and their message is
//! copied to `error` on the heap (an exception's message allocated in the
//! arena must not be read after the arena ends).
void local_surface_in_arena(const Mesh& solid, const detail::SolidIndex& index, const Mesh& block,
                            const std::vector<const Mesh*>& others, const Box3& region, const Box3& inner,
                            bool overlay_only, std::optional<Surface>& out);

std::optional<Surface> local_surface(const Mesh& solid, const detail::SolidIndex& index, const Mesh& block,
                                     const std::vector<const Mesh*>& others, const Box3& region, const Box3& inner,
                                     bool overlay_only, std::string& error) {
  detail::warm_up_exact_booleans();
  std::optional<Surface> out;
  const std::string failure =
      detail::run_in_arena([&] { local_surface_in_arena(solid, index, block, others, region, inner, overlay_only, out); });
  if (failure.empty()) return out;
  // CGAL's Self_intersection_exception: an operand self-intersects near the cut
  error = "exact boolean failed: " + failure;
  return std::nullopt;
}

//! Fills `out` (under a SuspendArena) with the surface; leaves it empty when
//! it cannot be made. The solid is clipped to `region`, the blocks to
//! `inner` (inside it, no plane shared): the two clips' cut faces are never
//! coplanar (CGAL's corefinement of large overlapping coplanar cut faces was
//! the measure's dominant cost). Faces on the planes of either box are cut
//! faces, not surface (those on `inner`'s planes lie outside the core
//! widened by the reach, see measure_region()).
//! The surface is made by successive CGAL unions (fast), or, when one fails
//! (its result would not be a 2-manifold: operands touching along an edge
//! or at a point) or `overlay_only`, by union_surface() on the same operands.
void local_surface_in_arena(const Mesh& solid, const detail::SolidIndex& index, const Mesh& block,
                            const std::vector<const Mesh*>& others, const Box3& region, const Box3& inner,
                            bool overlay_only, std::optional<Surface>& out) {
  std::vector<ExactMesh> operands;
  const BoundingBox rb{inner.min, inner.max};
  std::vector<const Mesh*> blocks{&block};
  blocks.insert(blocks.end(), others.begin(), others.end());
  for (const Mesh* o : blocks) {
    ExactMesh e = detail::to_exact(*o);
    if (!inside(bounding_box(*o), rb)) {
      ExactMesh box = detail::box_mesh(inner), clipped;
      if (!PMP::corefine_and_compute_intersection(e, box, clipped, kThrowOnSelfIntersection,
                                                  kThrowOnSelfIntersection) ||
          !CGAL::is_valid_polygon_mesh(clipped))
        return;
      e = std::move(clipped);
    }
    if (e.number_of_faces() > 0) operands.push_back(std::move(e));
  }
  for (ExactMesh& p : detail::clip_solid_to_box(solid, index, region)) operands.push_back(std::move(p));
  // Successive unions; when one fails (not a 2-manifold), the overlay of all
  // the operands. Setting aside only the operand whose union failed and
  // uniting the rest crashed inside CGAL on fertility at 1e-3 (a union the
  // first failure used to stop before): the unions stop at the first failure.
  // The unions work on copies (the overlay needs the operands as they were).
  for (const ExactMesh& e : operands)
    if (detail::has_coincident_vertices(e)) return;  // CGAL's corefinement precondition: it can loop
  std::vector<ExactMesh> parts;
  if (!overlay_only) {
    ExactMesh v;
    bool united = true;
    for (std::size_t k = 0; k < operands.size() && united; ++k) {
      ExactMesh e = operands[k];
      if (v.number_of_faces() == 0) {
        v = std::move(e);
        continue;
      }
      ExactMesh u;
      // CGAL 5.5 can report success with a broken result: on fertility at
      // 1e-3 (validate check 10, data/regression/fertility_fill_*.obj) a
      // union whose output has faces around a null vertex, which crashed
      // reading its points (the "race" of branch fillm2 at --threads 2: it
      // is deterministic, --threads 1 reaches that box later). Checked.
      united = PMP::corefine_and_compute_union(v, e, u, kThrowOnSelfIntersection, kThrowOnSelfIntersection) &&
               CGAL::is_valid_polygon_mesh(u) && !detail::has_coincident_vertices(u);
      if (united) v = std::move(u);
    }
    if (united) parts.push_back(std::move(v));
  }
  if (parts.empty()) parts = std::move(operands);
  std::vector<std::pair<std::size_t, detail::FaceIndex>> kept;  // (part, face)
  if (parts.size() == 1) {
    for (auto f : parts[0].faces()) kept.emplace_back(0, f);
  } else if (!detail::union_surface(parts, kept)) {
    return;
  }
  auto mesh_of = [&](std::size_t k) -> const ExactMesh& { return parts[k]; };
  const detail::ExactKernel::FT lo[3] = {region.min.x(), region.min.y(), region.min.z()};
  const detail::ExactKernel::FT hi[3] = {region.max.x(), region.max.y(), region.max.z()};
  const detail::ExactKernel::FT in_lo[3] = {inner.min.x(), inner.min.y(), inner.min.z()};
  const detail::ExactKernel::FT in_hi[3] = {inner.max.x(), inner.max.y(), inner.max.z()};
  std::vector<std::pair<std::size_t, detail::FaceIndex>> surface;
  std::vector<char> within;  // per entry of `surface`: inside the closed inner box
  for (const auto& [k, f] : kept) {
    const ExactMesh& m = mesh_of(k);
    const auto h = m.halfedge(f);
    const detail::ExactPoint* c[3] = {&m.point(m.source(h)), &m.point(m.target(h)), &m.point(m.target(m.next(h)))};
    bool on_plane = false;
    for (int i = 0; i < 3 && !on_plane; ++i)
      for (const auto* plane : {&lo[i], &hi[i], &in_lo[i], &in_hi[i]})
        if ((*c[0])[i] == *plane && (*c[1])[i] == *plane && (*c[2])[i] == *plane) on_plane = true;
    if (on_plane) continue;
    surface.emplace_back(k, f);
    bool in = true;
    for (int q = 0; q < 3 && in; ++q)
      for (int i = 0; i < 3 && in; ++i) in = in_lo[i] <= (*c[q])[i] && (*c[q])[i] <= in_hi[i];
    within.push_back(in ? 1 : 0);
  }
  {
    detail::SuspendArena heap;
    out.emplace();
    out->in_inner = within;
    // each vertex rounded once from its exact value (as to_double() does)
    std::vector<std::vector<int>> vertex(parts.size());
    for (const auto& [k, f] : surface) {
      const ExactMesh& m = mesh_of(k);
      std::vector<int>& index_of = vertex[k];
      if (index_of.empty()) index_of.assign(m.num_vertices(), -1);
      Triangle t{};
      int q = 0;
      for (auto x : CGAL::vertices_around_face(m.halfedge(f), m)) {
        int& id = index_of[x.idx()];
        if (id < 0) {
          const detail::ExactPoint& p = m.point(x);
          id = static_cast<int>(out->mesh.vertices.size());
          out->mesh.vertices.emplace_back(CGAL::to_double(CGAL::exact(p.x())), CGAL::to_double(CGAL::exact(p.y())),
                                          CGAL::to_double(CGAL::exact(p.z())));
        }
        if (q < 3) t[static_cast<std::size_t>(q)] = id;
        ++q;
      }
      out->faces.push_back(static_cast<int>(out->mesh.faces.size()));
      out->mesh.faces.push_back(t);
    }
    std::vector<ExactMesh>().swap(parts);
  }
}

}  // namespace

double rounding_slack(const Mesh& mesh) {
  const BoundingBox b = bounding_box(mesh);
  if (b.is_empty()) return 0.0;
  const double m = std::max(b.min.cwiseAbs().maxCoeff(), b.max.cwiseAbs().maxCoeff());
  return 16.0 * std::numeric_limits<double>::epsilon() * m;
}

namespace {

//! Boxes closer than `distance` (>= 0; 0 = none merged) replaced by their
//! bounding box, repeatedly: their regions would overlap, and one region
//! costs less than several. Deterministic (input order).
std::vector<BoundingBox> merge_close(std::vector<BoundingBox> boxes, double distance) {
  for (bool merged = true; merged && distance > 0;) {
    merged = false;
    for (std::size_t a = 0; a < boxes.size() && !merged; ++a)
      for (std::size_t b = a + 1; b < boxes.size() && !merged; ++b)
        if (detail::boxes_touch(widened(boxes[a], distance / 2), widened(boxes[b], distance / 2))) {
          boxes[a].extend(boxes[b].min);
          boxes[a].extend(boxes[b].max);
          boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(b));
          merged = true;
        }
  }
  return boxes;
}

//! The reach of the first pass of measure_cores().
double first_reach(const FillDeviationOptions& o) {
  return o.first_reach_fraction * o.reach;
}

//! A block and the boxes that cover where it can deviate.
struct Job {
  const Mesh* block;
  std::vector<BoundingBox> cores;
};

//! The deviation of each job: the maximum of measure_region() over its
//! boxes. First at the reach r1 = first_reach() (boxes closer than 2 r1
//! merged); a box whose bound exceeds r1 is measured again at the full
//! reach (those of a job closer than twice the reach merged): a measure at
//! reach r is an upper bound of the true distance, and equal to it (within
//! the error bound) when it is <= r (see the header), so the second pass is
//! needed only there. Tasks run in parallel when `parallel`; the result
//! does not depend on the thread count.
std::vector<FillDeviation> measure_cores(const FillDeviationMeter& meter, const std::vector<Job>& jobs,
                                         const std::vector<const Mesh*>& others, const FillDeviationOptions& options,
                                         bool parallel, bool local,
                                         const std::function<void(std::size_t, std::size_t)>& on_done) {
  std::vector<FillDeviation> deviation(jobs.size());
  for (FillDeviation& d : deviation) d.error = options.error;
  std::atomic<std::size_t> done{0};
  std::size_t total = 0;
  auto run = [&](const std::vector<std::pair<std::size_t, BoundingBox>>& tasks, double reach) {
    std::vector<FillDeviation> out(tasks.size());
    FillDeviationOptions o = options;
    o.reach = reach;
    total += tasks.size();
    auto one = [&](std::size_t t) {
      out[t] = meter.measure_region(*jobs[tasks[t].first].block, others, tasks[t].second, o);
      if (on_done) on_done(++done, total);
    };
    if (parallel)
      parallel_for(0, tasks.size(), one);
    else
      for (std::size_t t = 0; t < tasks.size(); ++t) one(t);
    return out;
  };
  auto add = [&](FillDeviation& d, const FillDeviation& m) {
    if (!d.failure.empty()) return;
    d.failure = m.failure;
    d.to_input = std::max(d.to_input, m.to_input);
    d.from_input = std::max(d.from_input, m.from_input);
  };
  // Pass 0: each box measured locally (measure_local(), an upper bound);
  // kept when within the reach, else measured by the two reaches below.
  std::vector<std::vector<BoundingBox>> pending(jobs.size());
  if (local) {
    std::vector<BoundingBox> cover;
    for (const Job& j : jobs) cover.insert(cover.end(), j.cores.begin(), j.cores.end());
    for (const Mesh* o : others)
      if (std::none_of(jobs.begin(), jobs.end(), [&](const Job& j) { return j.block == o; }))
        cover.push_back(bounding_box(*o));
    const std::vector<char> outside = meter.faces_outside(cover);
    std::vector<std::pair<std::size_t, BoundingBox>> local;
    for (std::size_t i = 0; i < jobs.size(); ++i)
      for (const BoundingBox& b : jobs[i].cores) local.emplace_back(i, b);
    std::vector<FillDeviation> out(local.size());
    total += local.size();
    auto one = [&](std::size_t t) {
      out[t] = meter.measure_local(*jobs[local[t].first].block, others, local[t].second, outside, options);
      if (on_done) on_done(++done, total);
    };
    if (parallel)
      parallel_for(0, local.size(), one);
    else
      for (std::size_t t = 0; t < local.size(); ++t) one(t);
    for (std::size_t t = 0; t < local.size(); ++t) {
      const FillDeviation& m = out[t];
      if (m.failure.empty() && std::max(m.to_input, m.from_input) + options.error > options.reach)
        pending[local[t].first].push_back(local[t].second);
      else
        add(deviation[local[t].first], m);
    }
  } else {
    for (std::size_t i = 0; i < jobs.size(); ++i) pending[i] = jobs[i].cores;
  }
  const double first = first_reach(options);
  std::vector<std::pair<std::size_t, BoundingBox>> tasks;
  for (std::size_t i = 0; i < jobs.size(); ++i)
    for (const BoundingBox& b : merge_close(pending[i], 2 * first)) tasks.emplace_back(i, b);
  const std::vector<FillDeviation> measured = run(tasks, first);
  std::vector<std::vector<BoundingBox>> again(jobs.size());
  for (std::size_t t = 0; t < tasks.size(); ++t) {
    const FillDeviation& m = measured[t];
    if (m.failure.empty() && first < options.reach && std::max(m.to_input, m.from_input) + options.error > first)
      again[tasks[t].first].push_back(tasks[t].second);
    else
      add(deviation[tasks[t].first], m);
  }
  tasks.clear();
  for (std::size_t i = 0; i < jobs.size(); ++i)
    for (const BoundingBox& b : merge_close(again[i], 2 * options.reach)) tasks.emplace_back(i, b);
  const std::vector<FillDeviation> remeasured = run(tasks, options.reach);
  for (std::size_t t = 0; t < tasks.size(); ++t) add(deviation[tasks[t].first], remeasured[t]);
  return deviation;
}

void check_options(const FillDeviationOptions& options) {
  if (!(options.error > 0) || !(options.reach >= 0) ||
      !(options.first_reach_fraction > 0 && options.first_reach_fraction <= 1) || !(options.local_margin >= 0))
    throw InvalidArgumentError(
        "measure_fill_deviation: the error bound must be > 0, the reach >= 0, the first reach fraction in (0, 1] "
        "and the local margin >= 0");
}

// ------------------------------------------------------------ fill_columns
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

//! Exact sign of n.d of face f for the axis (dim k, sign s): the orientation
//! of the face projected along d onto the plane of the two other coordinates.
int facing(const Mesh& m, const Triangle& f, int k, int s) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  auto p = [&](int v) {
    const Vec3& q = m.vertices[static_cast<std::size_t>(v)];
    return Epick::Point_2(q[i], q[j]);
  };
  return s * static_cast<int>(CGAL::orientation(p(f[0]), p(f[1]), p(f[2])));
}

}  // namespace

std::optional<std::vector<BoundingBox>> fill_face_columns(const Mesh& carved, const Mesh& milled, Axis axis) {
  const int k = axis_index(axis) / 2, s = axis_index(axis) % 2 == 0 ? 1 : -1;
  auto h = [&](const Vec3& v) { return s * v[k]; };
  if (carved.vertices.empty()) return std::vector<BoundingBox>{};
  double base = std::numeric_limits<double>::infinity();
  for (const Vec3& v : carved.vertices) base = std::min(base, h(v));
  auto at_base = [&](const Mesh& m, const Triangle& f) {
    for (int v : f)
      if (h(m.vertices[static_cast<std::size_t>(v)]) != base) return false;
    return true;
  };
  // The milled shape: no vertex below the base, every face facing away from d on the base plane.
  for (const Vec3& v : milled.vertices)
    if (h(v) < base) return std::nullopt;
  for (const Triangle& f : milled.faces)
    if (facing(milled, f, k, s) < 0 && !at_base(milled, f)) return std::nullopt;
  // The column (box extended down to the base plane) of every face that can
  // bound the fill from above.
  std::vector<BoundingBox> boxes;
  auto add = [&](const Mesh& m, const Triangle& f) {
    BoundingBox b;
    for (int v : f) b.extend(m.vertices[static_cast<std::size_t>(v)]);
    if (s > 0)
      b.min[k] = base;
    else
      b.max[k] = -base;
    boxes.push_back(b);
  };
  for (const Triangle& f : carved.faces)
    if (facing(carved, f, k, s) < 0 && !at_base(carved, f)) add(carved, f);
  // A milled face facing d lies on the carved block's surface with the block
  // under it when its three vertices are vertices of the carved block and
  // lie in one carved face facing d that has the first of them as a corner
  // (exact: coplanar, and inside it in the projection along d).
  std::map<std::array<double, 3>, int> carved_vertex;
  for (std::size_t v = 0; v < carved.vertices.size(); ++v) {
    const Vec3& q = carved.vertices[v];
    carved_vertex.emplace(std::array<double, 3>{q.x(), q.y(), q.z()}, static_cast<int>(v));
  }
  std::vector<std::vector<int>> incident(carved.vertices.size());
  for (std::size_t f = 0; f < carved.faces.size(); ++f)
    for (int v : carved.faces[f]) incident[static_cast<std::size_t>(v)].push_back(static_cast<int>(f));
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  auto p3 = [](const Vec3& q) { return Epick::Point_3(q.x(), q.y(), q.z()); };
  auto p2 = [&](const Vec3& q) { return Epick::Point_2(q[i], q[j]); };
  auto on_carved = [&](const Triangle& f) {
    std::array<int, 3> id{};
    for (int q = 0; q < 3; ++q) {
      const Vec3& x = milled.vertices[static_cast<std::size_t>(f[q])];
      const auto it = carved_vertex.find({x.x(), x.y(), x.z()});
      if (it == carved_vertex.end()) return false;
      id[q] = it->second;
    }
    for (int t : incident[static_cast<std::size_t>(id[0])]) {
      const Triangle& c = carved.faces[static_cast<std::size_t>(t)];
      if (facing(carved, c, k, s) <= 0) continue;
      const Vec3 &a = carved.vertices[static_cast<std::size_t>(c[0])], &b = carved.vertices[static_cast<std::size_t>(c[1])],
                 &e = carved.vertices[static_cast<std::size_t>(c[2])];
      const CGAL::Orientation turn = CGAL::orientation(p2(a), p2(b), p2(e));
      bool in = true;
      for (int q = 0; q < 3 && in; ++q) {
        const Vec3& x = carved.vertices[static_cast<std::size_t>(id[q])];
        in = CGAL::orientation(p3(a), p3(b), p3(e), p3(x)) == CGAL::COPLANAR &&
             CGAL::orientation(p2(a), p2(b), p2(x)) != -turn && CGAL::orientation(p2(b), p2(e), p2(x)) != -turn &&
             CGAL::orientation(p2(e), p2(a), p2(x)) != -turn;
      }
      if (in) return true;
    }
    return false;
  };
  for (const Triangle& f : milled.faces)
    if (facing(milled, f, k, s) > 0 && !on_carved(f)) add(milled, f);
  return boxes;
}

std::vector<BoundingBox> tile_columns(const std::vector<BoundingBox>& boxes, const Mesh& milled, Axis axis) {
  const int k = axis_index(axis) / 2;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  // One box per tile of an 8 x 8 grid over the block's footprint (the
  // tile of each face's lowest corner): a ring of fill (a groove round the
  // block) gives the tiles along it, not one box over the whole block.
  const BoundingBox all = bounding_box(milled);
  const double tile = std::max(all.size()[i], all.size()[j]) / 8.0;
  std::map<std::pair<long, long>, BoundingBox> tiles;
  for (const BoundingBox& b : boxes) {
    const auto key = tile_of(b, all, i, j, tile);
    BoundingBox& t = tiles[key];
    t.extend(b.min);
    t.extend(b.max);
  }
  std::vector<BoundingBox> out;
  for (const auto& [key, b] : tiles) out.push_back(b);
  return out;
}

std::optional<std::vector<BoundingBox>> fill_columns(const Mesh& carved, const Mesh& milled, Axis axis) {
  const std::optional<std::vector<BoundingBox>> columns = fill_face_columns(carved, milled, axis);
  if (!columns) return std::nullopt;
  return tile_columns(*columns, milled, axis);
}

std::vector<BoundingBox> solid_columns(const Mesh& part, double merge_distance) {
  if (part.faces.empty()) return {};
  // connected components (faces sharing a vertex), and each one's lowest coordinates
  std::vector<int> parent(part.vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v)
      v = parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    return v;
  };
  for (const Triangle& f : part.faces)
    for (int q = 1; q < 3; ++q) parent[static_cast<std::size_t>(find(f[q]))] = find(f[0]);
  std::vector<Vec3> low(part.vertices.size(), Vec3::Constant(std::numeric_limits<double>::infinity()));
  for (std::size_t v = 0; v < part.vertices.size(); ++v) {
    Vec3& l = low[static_cast<std::size_t>(find(static_cast<int>(v)))];
    l = l.cwiseMin(part.vertices[v]);
  }
  const BoundingBox all = bounding_box(part);
  const double slack = rounding_slack(part);
  std::vector<BoundingBox> best;
  double best_volume = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double tile = std::max(all.size()[i], all.size()[j]) / 8.0;
    std::map<std::pair<long, long>, BoundingBox> tiles;
    for (const Triangle& f : part.faces) {
      BoundingBox b;
      for (int v : f) b.extend(part.vertices[static_cast<std::size_t>(v)]);
      b.min[k] = low[static_cast<std::size_t>(find(f[0]))][k];
      const auto key = tile_of(b, all, i, j, tile);
      BoundingBox& t = tiles[key];
      t.extend(b.min);
      t.extend(b.max);
    }
    std::vector<BoundingBox> boxes;
    double volume = 0.0;
    for (const auto& [key, b] : tiles) {
      boxes.push_back(widened(b, slack));
      volume += boxes.back().size().prod();
    }
    if (volume < best_volume) {
      best_volume = volume;
      best = std::move(boxes);
    }
  }
  return merge_close(std::move(best), merge_distance);
}

std::vector<FillDeviation> measure_fills(const FillDeviationMeter& meter, const std::vector<const Mesh*>& blocks,
                                         const std::vector<std::optional<std::vector<BoundingBox>>>& fills,
                                         const std::vector<const Mesh*>& filled, const FillDeviationOptions& options,
                                         const std::function<void(std::size_t, std::size_t)>& on_done) {
  if (fills.size() != blocks.size()) throw InvalidArgumentError("measure_fills: one fill entry per block expected");
  check_options(options);
  // A block whose fill is not bounded is measured in the columns of the
  // whole block (they cover it, so its fill too), never in one region
  // around it: such a region holds the block and everything near it, and
  // its exact booleans took more than 16 GB on cactus.off at 1e-3 (validate
  // check 10, two blocks of 5760 and 3842 faces whose part outside the input
  // is not a 2-manifold).
  std::vector<Job> jobs;
  for (std::size_t i = 0; i < blocks.size(); ++i) jobs.push_back({blocks[i], fills[i] ? *fills[i] : solid_columns(*blocks[i])});
  std::vector<FillDeviation> deviation = measure_cores(meter, jobs, filled, options, true, options.local_first, on_done);
  for (std::size_t i = 0; i < blocks.size(); ++i) deviation[i].error += rounding_slack(*blocks[i]);
  return deviation;
}

struct FillDeviationMeter::Impl {
  explicit Impl(const Mesh& s) : solid(s), index(s), diagonal(bounding_box(s).diagonal()) {}
  FillDeviation measure_at(const Mesh& block, const std::vector<const Mesh*>& others, const BoundingBox& box,
                           const FillDeviationOptions& options, const std::vector<char>* outside = nullptr) const;
  std::vector<char> faces_outside(const std::vector<BoundingBox>& cover) const;
  Mesh solid;
  detail::SolidIndex index;
  double diagonal;  // of the solid's bounding box
};

FillDeviationMeter::FillDeviationMeter(const Mesh& solid) : impl_(std::make_unique<Impl>(solid)) {}
FillDeviationMeter::~FillDeviationMeter() = default;
const Mesh& FillDeviationMeter::solid() const { return impl_->solid; }

FillDeviation FillDeviationMeter::measure(const Mesh& block, const std::vector<const Mesh*>& others,
                                          const FillDeviationOptions& options) const {
  check_options(options);
  return measure_cores(*this, {Job{&block, {bounding_box(block)}}}, others, options, false, false, {})[0];
}

FillDeviation FillDeviationMeter::measure_fill(const Mesh& block, const std::vector<const Mesh*>& others,
                                               const std::vector<BoundingBox>& fill,
                                               const FillDeviationOptions& options) const {
  check_options(options);
  FillDeviation d = measure_cores(*this, {Job{&block, fill}}, others, options, false, false, {})[0];
  d.error += rounding_slack(block);
  return d;
}

FillDeviation FillDeviationMeter::measure_region(const Mesh& block, const std::vector<const Mesh*>& others,
                                                 const BoundingBox& core, const FillDeviationOptions& options) const {
  check_options(options);
  return impl_->measure_at(block, others, core, options);
}

FillDeviation FillDeviationMeter::measure_local(const Mesh& block, const std::vector<const Mesh*>& others,
                                                const BoundingBox& core, const std::vector<char>& outside,
                                                const FillDeviationOptions& options) const {
  check_options(options);
  if (outside.size() != impl_->solid.faces.size())
    throw InvalidArgumentError("measure_local: one entry of `outside` per input face expected");
  return impl_->measure_at(block, others, core, options, &outside);
}

std::vector<char> FillDeviationMeter::faces_outside(const std::vector<BoundingBox>& cover) const {
  return impl_->faces_outside(cover);
}

std::vector<char> FillDeviationMeter::Impl::faces_outside(const std::vector<BoundingBox>& cover) const {
  std::vector<char> outside(solid.faces.size(), 1);
  for (const BoundingBox& b : cover)
    for (int f : index.faces_near_closed_box(Box3{b.min, b.max})) outside[static_cast<std::size_t>(f)] = 0;
  return outside;
}

FillDeviation FillDeviationMeter::Impl::measure_at(const Mesh& block, const std::vector<const Mesh*>& others,
                                                   const BoundingBox& box, const FillDeviationOptions& options,
                                                   const std::vector<char>* outside) const {
  FillDeviation d;
  d.error = options.error;
  // the local measure (outside != nullptr, see measure_cores()) makes V
  // around the box alone (reach 0); the distances still look up to the reach
  const double r = outside ? 0.0 : options.reach;
  const BoundingBox reach = widened(box, r);
  const std::vector<int> near = index.faces_near_closed_box(Box3{reach.min, reach.max});
  // Q: the input surface within r of the box, the near faces clipped to it
  // (a long face's far part lies farther than r: see the header). The region
  // holds Q; the local measure's also holds the near faces up to
  // local_margin x the solid's diagonal (room for the nearest points of Q's
  // points: where V's faces are cut by the region they are not taken, and
  // the bound is looser and exceeds the reach more often; egea at 5e-4: 59
  // of 67 boxes with the reach as the room, none with the faces whole).
  const Mesh q = detail::clipped_faces(solid, near, reach);
  BoundingBox around = box;
  for (const Vec3& v : q.vertices) around.extend(v);
  if (outside) {
    const double margin = std::max(options.reach, options.local_margin * diagonal);
    for (const Vec3& v : detail::clipped_faces(solid, near, widened(box, margin)).vertices) around.extend(v);
  }
  const double hair = 1e-6 * std::max(around.diagonal(), 1e-300) + options.error;
  const BoundingBox region = widened(around, r + hair);
  // The blocks are clipped to `inner` (see local_surface_in_arena()): it
  // still holds the core widened by the reach, where V's surface is ∂S'.
  const BoundingBox inner = widened(around, r + hair / 2);
  if (options.max_faces > 0) {
    const std::size_t in_region = index.faces_near_closed_box(Box3{region.min, region.max}).size();
    if (in_region > options.max_faces) {
      d.failure = "region too large to measure (" + std::to_string(in_region) + " input faces > " +
                  std::to_string(options.max_faces) + ")";
      return d;
    }
  }
  std::vector<const Mesh*> close;
  for (const Mesh* o : others) {
    if (o == &block) continue;
    // A block none of whose cover boxes meets the region adds nothing to the
    // solid there (its part in the region lies in the solid): left out.
    const auto cover = options.others_cover ? options.others_cover->find(o) : FillCoverMap::const_iterator{};
    const bool meets = options.others_cover && cover != options.others_cover->end()
                           ? std::any_of(cover->second.begin(), cover->second.end(),
                                         [&](const BoundingBox& c) { return detail::boxes_touch(c, region); })
                           : detail::boxes_touch(bounding_box(*o), region);
    if (meets) close.push_back(o);
  }
  std::string error;
  const std::optional<Surface> surface =
      local_surface(solid, index, block, close, Box3{region.min, region.max}, Box3{inner.min, inner.max},
                    options.overlay_only, error);
  if (!error.empty()) {
    d.failure = error;
    return d;
  }
  if (!surface) {
    d.failure = "the exact surface of the blocks and the solid could not be made (an operand touches itself)";
    return d;
  }
  detail::DistanceMesh patch, input_near, covered;
  detail::append_distance_patch(patch, surface->mesh, &surface->faces);
  const BoundingBox look = widened(region, options.reach);
  const std::vector<int> wide = index.faces_near_closed_box(Box3{look.min, look.max});
  detail::append_distance_patch(input_near, solid, &wide);
  detail::append_distance_patch(covered, q, nullptr);
  d.to_input = detail::one_sided_hausdorff(patch, input_near, options.error);
  if (!outside) {
    d.from_input = detail::one_sided_hausdorff(covered, patch, options.error);
    return d;
  }
  // Local measure: the faces of V inside the closed inner box are ∂S' (V's
  // surface in the open inner box is ∂S' there, and ∂S' is closed); the
  // input faces that meet no cover box are ∂S' too (∂S away from every fill
  // is on ∂S'). Faces of V reaching past the inner box may be input surface
  // that a block clipped away buries: not taken.
  std::vector<int> sure;
  for (std::size_t q = 0; q < surface->faces.size(); ++q)
    if (surface->in_inner[q]) sure.push_back(surface->faces[q]);
  detail::DistanceMesh target;
  detail::append_distance_patch(target, surface->mesh, &sure);
  std::vector<int> away;
  for (int f : wide)
    if ((*outside)[static_cast<std::size_t>(f)]) away.push_back(f);
  detail::append_distance_patch(target, solid, &away);
  d.from_input = detail::one_sided_hausdorff(covered, target, options.error);
  return d;
}

}  // namespace subfab
