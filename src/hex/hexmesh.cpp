// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/hexmesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "geometry/hausdorff_distance.h"
#include "hex/hex_topology.h"
#include "hex/surface_projector.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/hex/pillow_hex_mesh.h"
#include "subfab/hex/scaled_jacobian.h"
#include "subfab/hex/subdivide_hex_mesh.h"

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
//! centre) through the vertex, first hit beyond the vertex. Rays from one
//! centre cannot cross, so a cube or a section does not fold. The closest
//! point is the fallback (vertex outside, or no hit).
void place_pillow(HexMesh& mesh, const std::vector<Vec3>& anchors, const std::vector<int>& outer,
                  const detail::SurfaceProjector& projector) {
  std::vector<Vec3> inner(mesh.vertices.size());
  parallel_for(0, outer.size(), [&](std::size_t v) {
    if (outer[v] < 0) return;
    const Vec3 origin = mesh.vertices[v];
    Vec3 target = projector.closest_point(origin);
    inner[v] = origin;
    const Vec3 dir = origin - anchors[v];
    if (dir.norm() > 0 && projector.inside(origin))
      if (const auto hit = projector.first_hit(origin, dir.normalized()))
        if ((*hit - origin).norm() <= 3 * (target - origin).norm()) {  // not across a gap
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

HexMeshResult hexmesh(const Mesh& surface, const Skeleton* skeleton, const HexMeshOptions& options) {
  HexMeshResult r;
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
  {
    StageScope stage(progress, "tubular structure");
    // the core is sized from the maximal spheres: never larger than the
    // distance from the node to the surface
    Skeleton sized = r.resampled;
    for (std::size_t v = 0; v < sized.num_nodes(); ++v) {
      const double d = (projector.closest_point(sized.points[v]) - sized.points[v]).norm();
      if (d > 0) sized.radii[v] = std::min(sized.radii[v], d);
    }
    r.structure_info = build_tubular_structure(sized, options.tubular);
    r.structure = r.structure_info.mesh;
  }
  timer.lap("tubular structure");
  HexMesh mesh = r.structure;
  {
    StageScope stage(progress, "pillow");
    const std::vector<int> outer = pillow_hex_mesh(mesh);
    place_pillow(mesh, r.structure_info.vertex_anchor, outer, projector);
    int levels = options.subdivisions;
    if (levels < 0) {
      levels = 1;
      while (mesh.hexes.size() * (std::size_t{1} << (3 * (levels + 1))) <= options.max_hexes) ++levels;
    }
    r.subdivisions = levels;
  }
  timer.lap("pillow");
  // coarse to fine: optimise, split, put the new boundary vertices on the
  // surface, optimise again (an untangled mesh splits into an almost
  // untangled one, so each level only has small repairs to make)
  OptimizeHexMeshOptions oo = options.optimize;
  oo.progress = progress;
  const bool smooth = oo.smooth;
  oo.smooth = smooth && r.subdivisions == 0;  // smoothing a coarse level drags the core to the surface
  r.optimize = optimize_hex_mesh(mesh, surface, oo);
  for (int i = 0; i < r.subdivisions; ++i) {
    oo.smooth = smooth && i + 1 == r.subdivisions;
    std::vector<Vec3> targets;
    {
      StageScope stage(progress, "subdivide");
      mesh = subdivide_hex_mesh(mesh);
      targets = radial_targets(mesh, projector);
    }
    oo.targets = &targets;
    const double first_min = r.optimize.min_before;
    r.optimize = optimize_hex_mesh(mesh, surface, oo);
    r.optimize.min_before = std::min(first_min, r.optimize.min_before);
    oo.targets = nullptr;
  }
  timer.lap("subdivide + project + optimise");
  {
    StageScope stage(progress, "measure");
    r.mesh = std::move(mesh);
    r.check = check_hex_mesh(r.mesh);
    r.scaled_jacobian = scaled_jacobians(r.mesh);
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
  }
  timer.lap("measure");
  return r;
}

}  // namespace subfab
