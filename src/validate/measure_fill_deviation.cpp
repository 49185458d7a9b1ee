// SPDX-License-Identifier: GPL-3.0-or-later
// FillDeviationMeter: the surface deviation that blocks sticking out of a
// solid cause, near one of them (see measure_fill_deviation.h).
#include "subfab/validate/measure_fill_deviation.h"

#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <atomic>
#include <cmath>
#include <array>
#include <numeric>
#include <map>
#include <limits>
#include <optional>
#include <utility>

#include "geometry/clip_solid_to_box.h"
#include "geometry/deterministic_arena.h"
#include "geometry/exact_mesh.h"
#include "geometry/solid_index.h"
#include "geometry/surface_deviation.h"
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

bool boxes_meet(const BoundingBox& a, const BoundingBox& b) {
  return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}

BoundingBox widened(BoundingBox box, double margin) {
  box.min.array() -= margin;
  box.max.array() += margin;
  return box;
}

bool inside(const BoundingBox& inner, const BoundingBox& outer) {
  return (outer.min.array() <= inner.min.array()).all() && (inner.max.array() <= outer.max.array()).all();
}

//! One-sided Hausdorff distance from `from` to `to`, within `error`.
double hausdorff(const detail::DistanceMesh& from, const detail::DistanceMesh& to, double error) {
  if (from.number_of_faces() == 0) return 0.0;
  if (to.number_of_faces() == 0) return std::numeric_limits<double>::infinity();
  const auto no_match = PMP::parameters::match_faces(false);
  return PMP::bounded_error_Hausdorff_distance<CGAL::Sequential_tag>(from, to, error, no_match, no_match);
}

const auto kThrowOnSelfIntersection = CGAL::parameters::throw_on_self_intersection(true);

//! a := a ∪ b (exact); false when CGAL cannot (a non-manifold result), or
//! when either operand touches itself (two vertices at one exact point):
//! the corefinement's precondition, which it does not check and can loop on.
//! An operand that self-intersects near the cut throws
//! Self_intersection_exception (caught in local_surface(), inside its arena):
//! CGAL 5.5 does not check that precondition otherwise and can crash
//! (decimated_knight.off at --tolerance 5e-4: segfault in this union).
bool unite(ExactMesh& a, ExactMesh& b) {
  if (detail::has_coincident_vertices(a) || detail::has_coincident_vertices(b)) return false;
  ExactMesh out;
  if (!PMP::corefine_and_compute_union(a, b, out, kThrowOnSelfIntersection, kThrowOnSelfIntersection)) return false;
  // CGAL 5.5 can report success with a broken result (faces around a null
  // vertex: fertility at 1e-3, found on branch fillm3, where reading its
  // points segfaulted): refused like a failed union.
  if (!CGAL::is_valid_polygon_mesh(out)) return false;
  a = std::move(out);
  return true;
}

//! The surface of V = (block ∪ others) ∩ region ∪ (solid ∩ region) inside
//! the open region, as a double mesh and the list of its faces that are not
//! on the region's planes. Exact booleans in a deterministic arena.
struct Surface {
  Mesh mesh;
  std::vector<int> faces;  // faces of mesh not on a plane of the region
};

//! Exceptions are caught here, while the arena lives, and their message is
//! copied to `error` on the heap (an exception's message allocated in the
//! arena must not be read after the arena ends).
void local_surface_in_arena(const Mesh& solid, const detail::SolidIndex& index, const Mesh& block,
                            const std::vector<const Mesh*>& others, const Box3& region, const Box3& inner,
                            std::optional<Surface>& out);

std::optional<Surface> local_surface(const Mesh& solid, const detail::SolidIndex& index, const Mesh& block,
                                     const std::vector<const Mesh*>& others, const Box3& region, const Box3& inner,
                                     std::string& error) {
  detail::warm_up_exact_booleans();
  std::optional<Surface> out;
  const std::string failure =
      detail::run_in_arena([&] { local_surface_in_arena(solid, index, block, others, region, inner, out); });
  if (failure.empty()) return out;
  // CGAL's Self_intersection_exception: an operand self-intersects near the cut
  error = "exact boolean failed: " + failure;
  return std::nullopt;
}

//! Fills `out` (under a SuspendArena) with the surface; leaves it empty when
//! a union is not a 2-manifold. The solid is clipped to `region`, the blocks
//! to `inner` (inside it, no plane shared): the two clips' cut faces are
//! never coplanar (CGAL's corefinement of large overlapping coplanar cut
//! faces was the measure's dominant cost). Faces on the planes of either
//! box are cut faces, not surface (those on `inner`'s planes lie outside
//! the core widened by the reach, see measure_region()).
void local_surface_in_arena(const Mesh& solid, const detail::SolidIndex& index, const Mesh& block,
                            const std::vector<const Mesh*>& others, const Box3& region, const Box3& inner,
                            std::optional<Surface>& out) {
  std::vector<ExactMesh> pieces = detail::clip_solid_to_box(solid, index, region);
  ExactMesh v;
  const BoundingBox rb{inner.min, inner.max};
  std::vector<const Mesh*> operands{&block};
  operands.insert(operands.end(), others.begin(), others.end());
  for (const Mesh* o : operands) {
    ExactMesh e = detail::to_exact(*o);
    if (!inside(bounding_box(*o), rb)) {
      ExactMesh box = detail::box_mesh(inner), clipped;
      if (!PMP::corefine_and_compute_intersection(e, box, clipped, kThrowOnSelfIntersection,
                                                  kThrowOnSelfIntersection) ||
          !CGAL::is_valid_polygon_mesh(clipped))
        return;
      e = std::move(clipped);
    }
    if (e.number_of_faces() == 0) continue;
    if (v.number_of_faces() == 0)
      v = std::move(e);
    else if (!unite(v, e))
      return;
  }
  for (ExactMesh& p : pieces) {
    if (v.number_of_faces() == 0)
      v = std::move(p);
    else if (!unite(v, p))
      return;
  }
  std::vector<char> on_plane(v.number_of_faces(), 0);
  const detail::ExactKernel::FT lo[3] = {region.min.x(), region.min.y(), region.min.z()};
  const detail::ExactKernel::FT hi[3] = {region.max.x(), region.max.y(), region.max.z()};
  const detail::ExactKernel::FT in_lo[3] = {inner.min.x(), inner.min.y(), inner.min.z()};
  const detail::ExactKernel::FT in_hi[3] = {inner.max.x(), inner.max.y(), inner.max.z()};
  std::size_t i = 0;
  for (auto f : v.faces()) {
    const auto h = v.halfedge(f);
    const detail::ExactPoint* c[3] = {&v.point(v.source(h)), &v.point(v.target(h)), &v.point(v.target(v.next(h)))};
    for (int k = 0; k < 3 && !on_plane[i]; ++k)
      for (const auto* plane : {&lo[k], &hi[k], &in_lo[k], &in_hi[k]})
        if ((*c[0])[k] == *plane && (*c[1])[k] == *plane && (*c[2])[k] == *plane) on_plane[i] = 1;
    ++i;
  }
  {
    detail::SuspendArena heap;
    out.emplace();
    out->mesh = detail::to_double(v);
    for (std::size_t f = 0; f < on_plane.size(); ++f)
      if (!on_plane[f]) out->faces.push_back(static_cast<int>(f));
    std::vector<ExactMesh>().swap(pieces);
  }
}

//! 16 ulps of the largest coordinate of `mesh`: the rounding slack of
//! measure_fill() (see the header).
double rounding_slack(const Mesh& mesh) {
  const BoundingBox b = bounding_box(mesh);
  if (b.is_empty()) return 0.0;
  const double m = std::max(b.min.cwiseAbs().maxCoeff(), b.max.cwiseAbs().maxCoeff());
  return 16.0 * std::numeric_limits<double>::epsilon() * m;
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

std::optional<std::vector<BoundingBox>> fill_columns(const Mesh& carved, const Mesh& milled, Axis axis) {
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
  // Boxes within merge_distance of each other become their bounding box
  // (their regions would overlap: one region costs less than several).
  for (bool merged = true; merged && merge_distance > 0;) {
    merged = false;
    for (std::size_t a = 0; a < best.size() && !merged; ++a)
      for (std::size_t b = a + 1; b < best.size() && !merged; ++b)
        if (boxes_meet(widened(best[a], merge_distance / 2), widened(best[b], merge_distance / 2))) {
          best[a].extend(best[b].min);
          best[a].extend(best[b].max);
          best.erase(best.begin() + static_cast<std::ptrdiff_t>(b));
          merged = true;
        }
  }
  return best;
}

std::vector<FillDeviation> measure_fills(const FillDeviationMeter& meter, const std::vector<const Mesh*>& blocks,
                                         const std::vector<std::optional<std::vector<BoundingBox>>>& fills,
                                         const std::vector<const Mesh*>& filled, const FillDeviationOptions& options,
                                         const std::function<void(std::size_t, std::size_t)>& on_done) {
  if (fills.size() != blocks.size()) throw InvalidArgumentError("measure_fills: one fill entry per block expected");
  std::vector<std::pair<std::size_t, std::optional<BoundingBox>>> tasks;  // (block, box; none = whole block)
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!fills[i])
      tasks.emplace_back(i, std::nullopt);
    else
      for (const BoundingBox& b : *fills[i]) tasks.emplace_back(i, b);
  }
  std::vector<FillDeviation> measured(tasks.size());
  std::atomic<std::size_t> done{0};
  parallel_for(0, tasks.size(), [&](std::size_t t) {
    const auto& [i, core] = tasks[t];
    const Mesh& block = *blocks[i];
    measured[t] = core ? meter.measure_fill(block, filled, {*core}, options) : meter.measure(block, filled, options);
    if (on_done) on_done(++done, tasks.size());
  });
  std::vector<FillDeviation> deviation(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i)
    if (fills[i]) deviation[i] = meter.measure_fill(*blocks[i], {}, {}, options);  // no box: 0 + the error bound
  for (std::size_t t = 0; t < tasks.size(); ++t) {
    FillDeviation& d = deviation[tasks[t].first];
    const FillDeviation& m = measured[t];
    if (!d.failure.empty()) continue;
    d.failure = m.failure;
    d.to_input = std::max(d.to_input, m.to_input);
    d.from_input = std::max(d.from_input, m.from_input);
    d.error = std::max(d.error, m.error);
  }
  return deviation;
}

struct FillDeviationMeter::Impl {
  explicit Impl(const Mesh& s) : solid(s), index(s) {}
  Mesh solid;
  detail::SolidIndex index;
};

FillDeviationMeter::FillDeviationMeter(const Mesh& solid) : impl_(std::make_unique<Impl>(solid)) {}
FillDeviationMeter::~FillDeviationMeter() = default;
const Mesh& FillDeviationMeter::solid() const { return impl_->solid; }

FillDeviation FillDeviationMeter::measure(const Mesh& block, const std::vector<const Mesh*>& others,
                                          const FillDeviationOptions& options) const {
  return measure_region(block, others, bounding_box(block), options);
}

FillDeviation FillDeviationMeter::measure_fill(const Mesh& block, const std::vector<const Mesh*>& others,
                                               const std::vector<BoundingBox>& fill,
                                               const FillDeviationOptions& options) const {
  if (!(options.error > 0) || !(options.reach >= 0))
    throw InvalidArgumentError("measure_fill_deviation: the error bound must be > 0 and the reach >= 0");
  FillDeviation d;
  d.error = options.error + rounding_slack(block);
  for (const BoundingBox& core : fill) {
    const FillDeviation r = measure_region(block, others, core, options);
    if (!r.failure.empty()) {
      d.failure = r.failure;
      return d;
    }
    d.to_input = std::max(d.to_input, r.to_input);
    d.from_input = std::max(d.from_input, r.from_input);
  }
  return d;
}

FillDeviation FillDeviationMeter::measure_region(const Mesh& block, const std::vector<const Mesh*>& others,
                                                 const BoundingBox& box, const FillDeviationOptions& options) const {
  if (!(options.error > 0) || !(options.reach >= 0))
    throw InvalidArgumentError("measure_fill_deviation: the error bound must be > 0 and the reach >= 0");
  const Mesh& solid = impl_->solid;
  FillDeviation d;
  d.error = options.error;
  const BoundingBox reach = widened(box, options.reach);
  const std::vector<int> near = impl_->index.faces_near_closed_box(Box3{reach.min, reach.max});
  BoundingBox around = box;
  for (int f : near)
    for (int v : solid.faces[static_cast<std::size_t>(f)]) around.extend(solid.vertices[static_cast<std::size_t>(v)]);
  const double hair = 1e-6 * std::max(around.diagonal(), 1e-300) + options.error;
  const BoundingBox region = widened(around, options.reach + hair);
  // The blocks are clipped to `inner` (see local_surface_in_arena()): it
  // still holds the core widened by the reach, where V's surface is ∂S'.
  const BoundingBox inner = widened(around, options.reach + hair / 2);
  if (options.max_faces > 0) {
    const std::size_t in_region = impl_->index.faces_near_closed_box(Box3{region.min, region.max}).size();
    if (in_region > options.max_faces) {
      d.failure = "region too large to measure (" + std::to_string(in_region) + " input faces > " +
                  std::to_string(options.max_faces) + ")";
      return d;
    }
  }
  std::vector<const Mesh*> close;
  for (const Mesh* o : others)
    if (o != &block && boxes_meet(bounding_box(*o), region)) close.push_back(o);
  std::string error;
  const std::optional<Surface> surface =
      local_surface(solid, impl_->index, block, close, Box3{region.min, region.max}, Box3{inner.min, inner.max}, error);
  if (!error.empty()) {
    d.failure = error;
    return d;
  }
  if (!surface) {
    d.failure = "exact union failed (the blocks and the solid touch along an edge or at a point)";
    return d;
  }
  detail::DistanceMesh patch, input_near, covered;
  detail::append_distance_patch(patch, surface->mesh, &surface->faces);
  const std::vector<int> wide = impl_->index.faces_near_closed_box(Box3{
      widened(region, options.reach).min, widened(region, options.reach).max});
  detail::append_distance_patch(input_near, solid, &wide);
  detail::append_distance_patch(covered, solid, &near);
  d.to_input = hausdorff(patch, input_near, options.error);
  d.from_input = hausdorff(covered, patch, options.error);
  return d;
}

}  // namespace subfab
