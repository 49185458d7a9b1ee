// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/hexmesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "geometry/hausdorff_distance.h"
#include "hex/hex_optimizers.h"
#include "hex/hex_topology.h"
#include "hex/surface_projector.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/hex/pillow_hex_mesh.h"
#include "subfab/hex/raise_min_scaled_jacobian.h"
#include "subfab/hex/scaled_jacobian.h"

namespace subfab {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

constexpr double kMaxCoreFraction = 0.6;  // see place_pillow()



class Timer {
 public:
  explicit Timer(std::vector<std::pair<std::string, double>>& out) : out_(out) {}
  void lap(const std::string& name) {
    const auto now = std::chrono::steady_clock::now();
    out_.emplace_back(name, std::chrono::duration<double>(now - start_).count());
    start_ = now;
  }

 private:
  std::vector<std::pair<std::string, double>>& out_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

//! Places the pillow's outer vertices on the surface: a ray from the
//! skeleton point each core vertex belongs to (its cube's or section's
//! centre) through the vertex, first hit. Rays from one centre cannot cross,
//! so a cube or a section does not fold. The ray starts at the centre, not at
//! the vertex, so a core vertex that pokes out of the surface (a cube corner
//! at a rounded tip) is pulled back in like the others instead of leaving its
//! padding hexahedra inside out. The closest point is the fallback (centre
//! outside, no hit, or a hit across a gap).
void place_pillow(HexMesh& mesh, const std::vector<Vec3>& anchors, const std::vector<int>& outer,
                  const detail::SurfaceProjector& projector) {
  std::vector<Vec3> inner(mesh.vertices.size());
  parallel_for(0, outer.size(), [&](std::size_t v) {
    if (outer[v] < 0) return;
    const Vec3 origin = mesh.vertices[v];
    Vec3 target = projector.closest_point(origin);
    inner[v] = origin;
    const Vec3 dir = origin - anchors[v];
    if (dir.norm() > 0 && projector.inside(anchors[v]))
      if (const auto hit = projector.first_hit(anchors[v], dir.normalized()))
        if ((*hit - origin).norm() <= 3 * (target - origin).norm() + dir.norm()) {  // not across a gap
          target = *hit;
          // keep the padding layer thick: the core vertex at most
          // kMaxCoreFraction of the way from its centre to the surface
          const double reach = (target - anchors[v]).norm();
          if (dir.norm() > kMaxCoreFraction * reach) inner[v] = anchors[v] + kMaxCoreFraction * reach * dir.normalized();
        }
    mesh.vertices[idx(outer[v])] = target;
  }, 256);
  for (std::size_t v = 0; v < outer.size(); ++v)
    if (outer[v] >= 0) mesh.vertices[v] = inner[v];
}

//! Signed distance to the surface: positive inside.
double depth(const detail::SurfaceProjector& projector, const Vec3& p) {
  const double d = (projector.closest_point(p) - p).norm();
  return projector.inside(p) ? d : -d;
}

//! The curve-skeleton can run close to the surface, or out of it, where the
//! shape is flat (rocker arm: a branching node 0.004 from the surface with a
//! radius of 0.11, so its cube was 50 times smaller than its tubes). Moves
//! each node whose depth (distance to the surface, negative outside) is
//! under half its radius away from its closest surface point (towards it
//! when outside), in steps of half to a sixteenth of its radius, while the
//! depth grows, and at most its radius in all: onto the middle of the part
//! it is in. Nodes are independent: parallel and deterministic.
void centre_skeleton_nodes(Skeleton& s, const detail::SurfaceProjector& projector) {
  std::vector<Vec3> moved = s.points;
  parallel_for(0, s.num_nodes(), [&](std::size_t v) {
    const double r = s.radii[v];
    const Vec3 start = s.points[v];
    Vec3 p = start;
    double d = depth(projector, p);
    if (d >= 0.5 * r) return;
    // the step and the reach: the radius, or twice the way back in for a
    // node outside (its radius is often that distance, not the part's)
    const double scale = std::max(r, -2 * d);
    for (int iter = 0; iter < 64; ++iter) {
      Vec3 dir = p - projector.closest_point(p);
      if (!(dir.norm() > 0)) break;
      dir = (d < 0 ? -dir : dir).normalized();
      bool improved = false;
      for (double step = 0.5 * scale; step > scale / 20; step *= 0.5) {
        const Vec3 q = p + step * dir;
        if ((q - start).norm() > scale) continue;
        if (const double dq = depth(projector, q); dq > d + 1e-9 * scale) {
          p = q, d = dq, improved = true;
          break;
        }
      }
      if (!improved) break;
    }
    moved[v] = p;
  }, 8);
  s.points = std::move(moved);
}

//! A terminal node at (or near) the end of its limb leaves its cube no room:
//! the cube pokes out of the surface and the padding around it folds (the
//! curve-skeleton of a rounded tip ends on the surface). Moves each terminal
//! node towards its neighbour, up to half way, to the first of 16 evenly
//! spaced points whose distance to the surface reaches the neighbour's
//! (capped) radius, or the farthest one from the surface if none does. The
//! radii must already be capped by the distance to the surface.
void pull_in_terminal_nodes(Skeleton& s, const detail::SurfaceProjector& projector) {
  constexpr int kSamples = 16;
  for (std::size_t v = 0; v < s.num_nodes(); ++v) {
    if (s.neighbors[v].size() != 1) continue;
    const std::size_t w = idx(s.neighbors[v][0]);
    const Vec3 from = s.points[v], to = s.points[w];
    const double want = s.radii[w];
    Vec3 best = from;
    double best_d = projector.inside(from) ? (projector.closest_point(from) - from).norm() : 0.0;
    if (best_d >= want) continue;
    for (int i = 1; i <= kSamples; ++i) {
      const Vec3 p = from + (0.5 * i / kSamples) * (to - from);
      const double d = projector.inside(p) ? (projector.closest_point(p) - p).norm() : 0.0;
      if (d > best_d) best = p, best_d = d;
      if (d >= want) break;
    }
    s.points[v] = best;
    s.radii[v] = std::min(want, best_d);  // its old radius was capped by its old depth
  }
}

//! Where each boundary vertex goes on the surface: along the pillow edge
//! that joins it to the interior, a ray from the inner end of that edge
//! through the vertex, first hit (closest point when it misses or jumps a
//! gap). Used after each subdivision, so new boundary vertices follow the
//! shape level by level without the folds a closest-point projection makes
//! across thin parts. The optimiser moves them there in valid steps.
std::vector<Vec3> radial_targets(const HexMesh& mesh, const detail::SurfaceProjector& projector) {
  const detail::HexTopology topo = detail::hex_topology(mesh);
  std::vector<Vec3> next = mesh.vertices;
  parallel_for(0, mesh.vertices.size(), [&](std::size_t v) {
    if (!topo.on_boundary[v]) return;
    Vec3 dir = Vec3::Zero();
    Vec3 inner = Vec3::Zero();
    int count = 0;
    for (int w : topo.neighbors[v])
      if (!topo.on_boundary[idx(w)]) {
        inner += mesh.vertices[idx(w)];
        ++count;
      }
    if (count > 0) {
      inner /= count;
      dir = mesh.vertices[v] - inner;
    }
    const Vec3 closest = projector.closest_point(mesh.vertices[v]);
    next[v] = closest;
    // the ray's hit, unless it jumped across a gap to another part
    if (const auto hit = dir.norm() > 0 ? projector.first_hit(inner, dir.normalized()) : std::nullopt)
      if ((*hit - mesh.vertices[v]).norm() <= 2 * (closest - mesh.vertices[v]).norm() + 0.25 * dir.norm())
        next[v] = *hit;
  }, 256);
  return next;
}

}  // namespace

namespace {

//! hexmesh() without the layer-keeping trial.
HexMeshResult hexmesh_once(const Mesh& surface, const Skeleton* skeleton, const HexMeshOptions& options) {
  HexMeshResult r;
  r.resolution_control = options.resolution_control;
  r.keep_layers = options.keep_layers;
  Timer timer(r.timings);
  Progress* progress = options.progress;
  r.diagonal = bounding_box(surface).diagonal();
  if (skeleton) {
    check_skeleton(*skeleton);
    if (skeleton->num_nodes() == 0) throw InvalidArgumentError("the skeleton has no node");
    r.skeleton = *skeleton;
  } else {
    ComputeSkeletonOptions so = options.skeleton;
    so.progress = progress;
    r.skeleton = compute_skeleton(surface, so);
  }
  timer.lap("skeleton");
  {
    StageScope stage(progress, "resample skeleton");
    r.resampled = resample_skeleton(r.skeleton, options.resample);
  }
  timer.lap("resample");
  const detail::SurfaceProjector projector(surface);
  Skeleton sized = r.resampled;  // the skeleton the structure is built on
  {
    StageScope stage(progress, "tubular structure");
    // the core is sized from the maximal spheres: never larger than the
    // distance from the node to the surface
    centre_skeleton_nodes(sized, projector);
    for (std::size_t v = 0; v < sized.num_nodes(); ++v) {
      const double d = (projector.closest_point(sized.points[v]) - sized.points[v]).norm();
      if (d > 0) sized.radii[v] = std::min(sized.radii[v], d);
    }
    pull_in_terminal_nodes(sized, projector);
    r.structure_info = build_tubular_structure(sized, options.tubular);
    r.structure = r.structure_info.mesh;
  }
  timer.lap("tubular structure");
  HexMesh mesh = r.structure;
  {
    StageScope stage(progress, "pillow");
    const std::vector<int> outer = pillow_hex_mesh(mesh);
    place_pillow(mesh, r.structure_info.vertex_anchor, outer, projector);
  }
  timer.lap("pillow");
  // resolution control (D.5): splits per hexahedron; without it (or without
  // cones) every hexahedron splits equally
  if (options.resolution_control) {
    StageScope stage(progress, "resolution control");
    r.cones_found = detect_cones(r.structure_info, sized, options.resolution);
    std::vector<Cone> used = r.cones_found;
    r.resolution = control_resolution(mesh, used, options.resolution);
    // the automatic choice keeps the bound: while one split of the least
    // split hexahedra would already exceed it, the cone with the smallest
    // ratio is dropped (each cone doubles the resolution of a whole part)
    double seconds = r.resolution.ilp_seconds;
    while (options.subdivisions < 0 && !used.empty() && planned_num_hexes(r.resolution, 1) > options.max_hexes) {
      used.erase(std::min_element(used.begin(), used.end(),
                                  [](const Cone& a, const Cone& b) { return a.ratio < b.ratio; }));
      r.resolution = control_resolution(mesh, used, options.resolution);
      seconds += r.resolution.ilp_seconds;
    }
    r.resolution.ilp_seconds = seconds;
    r.resolution.num_cones_found = r.cones_found.size();
  } else {
    r.resolution.splits.assign(mesh.hexes.size(), 0);
    r.resolution.layer_of.assign(mesh.hexes.size(), -1);
  }
  int offset = options.subdivisions;
  if (offset < 0) {
    offset = 1;
    if (options.keep_layers)  // the finest level splits across the tubes only: count it exactly
      while (num_hexes_keeping_layers(mesh, r.resolution, offset + 1, options.keep_layers_share) <= options.max_hexes)
        ++offset;
    else
      while (planned_num_hexes(r.resolution, offset + 1) <= options.max_hexes) ++offset;
  }
  r.min_subdivisions = offset;
  RefinementSchedule schedule = schedule_refinement(r.resolution, offset, r.subdivisions);
  timer.lap("resolution control");
  // coarse to fine: optimise, split, put the new boundary vertices on the
  // surface, optimise again (an untangled mesh splits into an almost
  // untangled one, so each level only has small repairs to make)
  OptimizeHexMeshOptions oo = options.optimize;
  oo.progress = progress;
  const bool smooth = oo.smooth;
  oo.smooth = smooth && r.subdivisions == 0;  // smoothing a coarse level drags the core to the surface
  r.optimize = detail::optimize_hex_mesh(mesh, projector, oo);
  for (int i = 0; i < r.subdivisions; ++i) {
    oo.smooth = smooth && i + 1 == r.subdivisions;
    std::vector<Vec3> targets;
    {
      StageScope stage(progress, "subdivide");
      if (options.keep_layers && i + 1 == r.subdivisions) {
        const auto axes = layer_keeping_axes(mesh, schedule, i + 1, options.keep_layers_share, &r.kept_layer_sheets);
        mesh = refine_hex_mesh(mesh, schedule, i + 1, &axes);
      } else {
        mesh = refine_hex_mesh(mesh, schedule, i + 1);
      }
      targets = radial_targets(mesh, projector);
    }
    oo.targets = &targets;
    const double first_min = r.optimize.min_before;
    r.optimize = detail::optimize_hex_mesh(mesh, projector, oo);
    r.optimize.min_before = std::min(first_min, r.optimize.min_before);
    oo.targets = nullptr;
  }
  timer.lap("subdivide + project + optimise");
  if (options.raise_min) {
    StageScope stage(progress, "raise worst elements");
    r.raise = detail::raise_min_scaled_jacobian(mesh, projector, options.raise);
  }
  timer.lap("raise worst elements");
  // the worst elements first, then the boundary onto the surface where the
  // patch's worst element stays over the mesh's minimum (so that minimum is
  // kept), then the average
  if (options.raise_worst) {
    StageScope stage(progress, "raise worst elements jointly");
    r.worst = detail::raise_worst_scaled_jacobian(mesh, projector, options.worst);
  }
  timer.lap("raise worst jointly");
  if (options.pull_boundary) {
    StageScope stage(progress, "pull boundary to surface");
    r.pull = detail::pull_boundary_to_surface(mesh, projector, options.pull);
  }
  timer.lap("pull boundary");
  if (options.raise_mean) {
    StageScope stage(progress, "raise average quality");
    r.mean = detail::raise_mean_scaled_jacobian(mesh, projector, options.mean);
  }
  timer.lap("raise average quality");
  {
    StageScope stage(progress, "measure");
    r.mesh = std::move(mesh);
    r.check = check_hex_mesh(r.mesh);
    r.scaled_jacobian = scaled_jacobians(r.mesh);
    r.in_cone_template = std::move(schedule.template_of);
    const auto& sj = r.scaled_jacobian;
    if (!sj.empty()) {
      r.min_sj = *std::min_element(sj.begin(), sj.end());
      r.max_sj = *std::max_element(sj.begin(), sj.end());
      double sum = 0;
      for (double q : sj) {
        sum += q;
        const std::size_t bin = q <= 0 ? 0 : 1 + std::min<std::size_t>(9, static_cast<std::size_t>(std::ceil(q * 10) - 1));
        ++r.histogram[bin];
      }
      r.avg_sj = sum / static_cast<double>(sj.size());
    }
    // distance: mean over area-weighted samples of the boundary (to the
    // input surface, as Metro's mean); max = symmetric sampled Hausdorff
    Mesh boundary = boundary_triangles(r.mesh);
    remove_unreferenced_vertices(boundary);
    const detail::SurfaceDistance to_input(surface);
    const int n = 4;  // barycentric grid per triangle
    std::vector<double> sum(boundary.faces.size(), 0.0), area(boundary.faces.size(), 0.0);
    parallel_for(0, boundary.faces.size(), [&](std::size_t f) {
      const auto& t = boundary.faces[f];
      const Vec3 &a = boundary.vertices[idx(t[0])], &b = boundary.vertices[idx(t[1])], &c = boundary.vertices[idx(t[2])];
      double s = 0;
      int count = 0;
      for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j) {
          const double u = (i + 1.0 / 3) / n, v = (j + 1.0 / 3) / n;
          s += to_input(a + u * (b - a) + v * (c - a));
          ++count;
        }
      area[f] = 0.5 * (b - a).cross(c - a).norm();
      sum[f] = s / count;
    }, 64);
    double total = 0, weighted = 0;
    for (std::size_t f = 0; f < sum.size(); ++f) total += area[f], weighted += area[f] * sum[f];
    r.mean_distance = total > 0 ? weighted / total : 0.0;
    r.max_distance = detail::hausdorff_distance(boundary, surface, 100000);
    // the boundary's vertices alone (no chordal error): how far the
    // optimiser left them off the surface
    std::vector<double> at_vertex(boundary.vertices.size(), 0.0);
    parallel_for(0, boundary.vertices.size(), [&](std::size_t v) { at_vertex[v] = to_input(boundary.vertices[v]); }, 256);
    double vertex_sum = 0;
    for (double d : at_vertex) vertex_sum += d, r.max_vertex_distance = std::max(r.max_vertex_distance, d);
    r.boundary_vertices = at_vertex.size();
    for (double d : at_vertex) r.vertices_off_surface += d > 1e-6 * r.diagonal;
    r.mean_vertex_distance = at_vertex.empty() ? 0.0 : vertex_sum / static_cast<double>(at_vertex.size());
  }
  timer.lap("measure");
  return r;
}

double total_seconds(const HexMeshResult& r) {
  double t = 0;
  for (const auto& [stage, seconds] : r.timings) t += seconds;
  return t;
}

}  // namespace

HexMeshResult hexmesh(const Mesh& surface, const Skeleton* skeleton, const HexMeshOptions& options) {
  HexMeshResult r = hexmesh_once(surface, skeleton, options);
  const bool trial = options.layer_trial && !options.keep_layers && options.subdivisions < 0 &&
                     r.mesh.num_hexes() <= options.layer_trial_hexes && r.check.valid() && r.histogram[0] == 0;
  if (!trial) return r;
  HexMeshOptions alternative = options;
  alternative.layer_trial = false;
  alternative.keep_layers = true;
  alternative.resolution_control = false;
  HexMeshResult other;
  {
    StageScope stage(options.progress, "layer-keeping trial");
    other = hexmesh_once(surface, &r.skeleton, alternative);  // the same skeleton, not computed again
  }
  // kept only when no worse on any of the three measures (and valid)
  const bool better = other.check.valid() && other.histogram[0] == 0 && other.avg_sj >= r.avg_sj &&
                      other.min_sj >= r.min_sj && other.mean_distance <= r.mean_distance;
  HexMeshResult& kept = better ? other : r;
  const HexMeshResult& dropped = better ? r : other;
  LayerTrial t;
  t.tried = true;
  t.kept = better;
  t.hexes = dropped.mesh.num_hexes();
  t.avg_sj = dropped.avg_sj;
  t.min_sj = dropped.min_sj;
  t.mean_distance = dropped.mean_distance;
  t.seconds = total_seconds(dropped);
  kept.layer_trial = t;
  kept.timings.emplace_back(better ? "mesh without keeping layers (not kept)" : "layer-keeping trial (not kept)",
                            t.seconds);
  if (options.progress)
    options.progress->info(std::string("layer-keeping trial: ") + std::to_string(other.mesh.num_hexes()) +
                           " hexahedra at " + std::to_string(other.avg_sj) + " / " + std::to_string(other.min_sj) +
                           (better ? ", kept (no worse on average, minimum and distance)"
                                   : ", not kept (worse on average, minimum or distance)"));
  return std::move(kept);
}

}  // namespace subfab
