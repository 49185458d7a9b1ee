// SPDX-License-Identifier: GPL-3.0-or-later
// FillDeviationMeter: the surface deviation that blocks sticking out of a
// solid cause, near one of them (see measure_fill_deviation.h).
#include "subfab/validate/measure_fill_deviation.h"

#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/distance.h>

#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "geometry/clip_solid_to_box.h"
#include "geometry/deterministic_arena.h"
#include "geometry/exact_mesh.h"
#include "geometry/solid_index.h"
#include "geometry/surface_deviation.h"
#include "subfab/core/error.h"

namespace subfab {
namespace {

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

//! a := a ∪ b (exact); false when CGAL cannot (a non-manifold result), or
//! when either operand touches itself (two vertices at one exact point):
//! the corefinement's precondition, which it does not check and can loop on.
bool unite(ExactMesh& a, ExactMesh& b) {
  if (detail::has_coincident_vertices(a) || detail::has_coincident_vertices(b)) return false;
  ExactMesh out;
  if (!PMP::corefine_and_compute_union(a, b, out)) return false;
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

std::optional<Surface> local_surface(const Mesh& solid, const detail::SolidIndex& index, const Mesh& block,
                                     const std::vector<const Mesh*>& others, const Box3& region) {
  detail::warm_up_exact_booleans();
  std::optional<Surface> out;
  detail::DeterministicArena arena;
  std::vector<ExactMesh> pieces = detail::clip_solid_to_box(solid, index, region);
  ExactMesh v = detail::to_exact(block);
  const BoundingBox rb{region.min, region.max};
  for (const Mesh* o : others) {
    ExactMesh e = detail::to_exact(*o);
    if (!inside(bounding_box(*o), rb)) {
      ExactMesh box = detail::box_mesh(region), clipped;
      if (!PMP::corefine_and_compute_intersection(e, box, clipped)) return std::nullopt;
      e = std::move(clipped);
    }
    if (e.number_of_faces() > 0 && !unite(v, e)) return std::nullopt;
  }
  for (ExactMesh& p : pieces)
    if (!unite(v, p)) return std::nullopt;
  std::vector<char> on_plane(v.number_of_faces(), 0);
  const detail::ExactKernel::FT lo[3] = {region.min.x(), region.min.y(), region.min.z()};
  const detail::ExactKernel::FT hi[3] = {region.max.x(), region.max.y(), region.max.z()};
  std::size_t i = 0;
  for (auto f : v.faces()) {
    const auto h = v.halfedge(f);
    const detail::ExactPoint* c[3] = {&v.point(v.source(h)), &v.point(v.target(h)), &v.point(v.target(v.next(h)))};
    for (int k = 0; k < 3 && !on_plane[i]; ++k)
      for (const auto* plane : {&lo[k], &hi[k]})
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
  return out;
}

}  // namespace

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
  if (!(options.error > 0) || !(options.reach >= 0))
    throw InvalidArgumentError("measure_fill_deviation: the error bound must be > 0 and the reach >= 0");
  const Mesh& solid = impl_->solid;
  FillDeviation d;
  d.error = options.error;
  const BoundingBox box = bounding_box(block);
  const BoundingBox reach = widened(box, options.reach);
  const std::vector<int> near = impl_->index.faces_near_closed_box(Box3{reach.min, reach.max});
  BoundingBox around = box;
  for (int f : near)
    for (int v : solid.faces[static_cast<std::size_t>(f)]) around.extend(solid.vertices[static_cast<std::size_t>(v)]);
  const double hair = 1e-6 * std::max(around.diagonal(), 1e-300) + options.error;
  const BoundingBox region = widened(around, options.reach + hair);
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
  std::optional<Surface> surface;
  try {
    surface = local_surface(solid, impl_->index, block, close, Box3{region.min, region.max});
  } catch (const std::exception& e) {
    d.failure = std::string("exact boolean failed: ") + e.what();
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
