// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/hexmesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "geometry/hausdorff_distance.h"
#include "hex/surface_projector.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/hex/pillow_hex_mesh.h"
#include "subfab/hex/scaled_jacobian.h"
#include "subfab/hex/subdivide_hex_mesh.h"

namespace subfab {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

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

//! Places the pillow's outer vertices on the surface: a ray from each core
//! boundary vertex along its (area-weighted) boundary normal.
void place_pillow(HexMesh& mesh, const std::vector<Quad>& core_boundary, const std::vector<int>& outer,
                  const detail::SurfaceProjector& projector) {
  std::vector<Vec3> normal(mesh.vertices.size(), Vec3::Zero());
  for (const Quad& q : core_boundary) {
    const auto& p = mesh.vertices;
    const Vec3 n = (p[idx(q[2])] - p[idx(q[0])]).cross(p[idx(q[3])] - p[idx(q[1])]);
    for (int v : q) normal[idx(v)] += n;
  }
  parallel_for(0, outer.size(), [&](std::size_t v) {
    if (outer[v] < 0) return;
    const Vec3 origin = mesh.vertices[v];
    Vec3 target = projector.closest_point(origin);
    if (projector.inside(origin) && normal[v].norm() > 0)
      if (const auto hit = projector.first_hit(origin, normal[v].normalized())) target = *hit;
    mesh.vertices[idx(outer[v])] = target;
  }, 256);
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
  {
    StageScope stage(progress, "tubular structure");
    r.structure_info = build_tubular_structure(r.resampled, options.tubular);
    r.structure = r.structure_info.mesh;
  }
  timer.lap("tubular structure");
  const detail::SurfaceProjector projector(surface);
  HexMesh mesh = r.structure;
  {
    StageScope stage(progress, "pillow and subdivide");
    const std::vector<Quad> core_boundary = boundary_quads(mesh);
    const std::vector<int> outer = pillow_hex_mesh(mesh);
    place_pillow(mesh, core_boundary, outer, projector);
    int levels = options.subdivisions;
    if (levels < 0) {
      levels = 1;
      while (mesh.hexes.size() * (std::size_t{1} << (3 * (levels + 1))) <= options.max_hexes) ++levels;
    }
    r.subdivisions = levels;
    for (int i = 0; i < levels; ++i) mesh = subdivide_hex_mesh(mesh);
  }
  timer.lap("pillow + subdivide");
  {
    OptimizeHexMeshOptions oo = options.optimize;
    oo.progress = progress;
    r.optimize = optimize_hex_mesh(mesh, surface, oo);
  }
  timer.lap("project + optimise");
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
