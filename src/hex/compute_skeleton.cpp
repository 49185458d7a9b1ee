// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/compute_skeleton.h"

#ifndef CGAL_EIGEN3_ENABLED
#define CGAL_EIGEN3_ENABLED
#endif
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/extract_mean_curvature_flow_skeleton.h>

#include <cmath>
#include <string>
#include <vector>

#include "geometry/deterministic_arena.h"
#include "subfab/core/error.h"

namespace subfab {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Skeletonization = CGAL::Mean_curvature_flow_skeletonization<SurfaceMesh>;
using McfSkeleton = Skeletonization::Skeleton;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

SurfaceMesh to_surface_mesh(const Mesh& mesh) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> vi;
  vi.reserve(mesh.vertices.size());
  for (const Vec3& p : mesh.vertices) vi.push_back(sm.add_vertex(Point(p.x(), p.y(), p.z())));
  for (const Triangle& t : mesh.faces)
    if (sm.add_face(vi[static_cast<std::size_t>(t[0])], vi[static_cast<std::size_t>(t[1])],
                    vi[static_cast<std::size_t>(t[2])]) == SurfaceMesh::null_face())
      throw InvalidMeshError("compute_skeleton: the mesh is not an oriented 2-manifold (a face could not be added)");
  return sm;
}

//! A small closed UV sphere (8 x 5), for the warm-up.
Mesh small_sphere() {
  Mesh m;
  const int around = 8, rings = 5;
  m.vertices.push_back(Vec3(0, 0, -1));
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < around; ++j) {
      const double a = 3.141592653589793 * i / rings, b = 2 * 3.141592653589793 * j / around;
      m.vertices.push_back(Vec3(1.5 * std::sin(a) * std::cos(b), std::sin(a) * std::sin(b), -std::cos(a)));
    }
  m.vertices.push_back(Vec3(0, 0, 1));
  auto id = [&](int ring, int j) { return 1 + ring * around + (j + around) % around; };
  const int last = static_cast<int>(m.vertices.size()) - 1;
  for (int j = 0; j < around; ++j) m.faces.push_back({0, id(0, j + 1), id(0, j)});
  for (int i = 0; i + 2 < rings; ++i)
    for (int j = 0; j < around; ++j) {
      m.faces.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
    }
  for (int j = 0; j < around; ++j) m.faces.push_back({last, id(rings - 2, j), id(rings - 2, j + 1)});
  return m;
}

//! The flow's Delaunay step uses CGAL's lazy exact numbers, whose per-thread
//! constants are created on first use: create them on the ordinary heap, once
//! per thread, before any arena (an arena's memory is gone when it ends).
void warm_up_flow() {
  thread_local bool done = false;
  if (done) return;
  done = true;
  detail::SuspendArena heap;
  SurfaceMesh sm = to_surface_mesh(small_sphere());
  McfSkeleton mcf;
  Skeletonization skeletonize(sm);
  skeletonize(mcf);
}

}  // namespace

Skeleton compute_skeleton(const Mesh& mesh, const ComputeSkeletonOptions& options, ComputeSkeletonReport* report) {
  ComputeSkeletonReport r;
  Skeleton raw;
  {
    StageScope stage(options.progress, "skeleton (mean curvature flow)");
    // CGAL's flow orders some edge collapses by handle address: a private
    // bump allocator makes addresses follow allocation order, so the result
    // does not depend on the heap's history (threads, earlier work). Freed
    // memory is not reused here (reuse_freed = false): the skeletons, and the
    // hexahedral meshes measured in bench/RESULTS.md, stay those of the plain
    // bump allocator; the flow's memory is small.
    bool empty = false;
    warm_up_flow();
    // An exception must not carry arena memory out (its message would be
    // read after the arena is unmapped): run_in_arena() copies it to the heap.
    const std::string error = detail::run_in_arena([&] {
      SurfaceMesh sm = to_surface_mesh(mesh);
      McfSkeleton mcf;
      Skeletonization skeletonize(sm);
      skeletonize(mcf);
      const std::size_t n = boost::num_vertices(mcf);
      empty = n == 0;
      Tree tree(faces(sm).first, faces(sm).second, sm);
      tree.accelerate_distance_queries();
      std::vector<McfSkeleton::vertex_descriptor> order;
      for (auto v : CGAL::make_range(boost::vertices(mcf))) order.push_back(v);
      std::vector<std::pair<std::size_t, std::size_t>> edges;
      for (auto e : CGAL::make_range(boost::edges(mcf)))
        edges.emplace_back(static_cast<std::size_t>(boost::source(e, mcf)), static_cast<std::size_t>(boost::target(e, mcf)));
      std::vector<double> radii(n, 0.0);
      for (std::size_t i = 0; i < order.size(); ++i) {
        const auto& node = mcf[order[i]];
        double sum = 0;
        for (auto sv : node.vertices) sum += std::sqrt(CGAL::squared_distance(node.point, sm.point(sv)));
        double radius = node.vertices.empty() ? 0.0 : sum / static_cast<double>(node.vertices.size());
        if (!(radius > 0)) radius = std::sqrt(tree.squared_distance(node.point));
        radii[i] = radius;
      }
      detail::SuspendArena heap;  // the skeleton outlives the arena
      const double tiny = 1e-9 * bounding_box(mesh).diagonal();
      for (std::size_t i = 0; i < order.size(); ++i) {
        const auto& point = mcf[order[i]].point;
        raw.add_node(Vec3(point.x(), point.y(), point.z()), radii[i] > 0 ? radii[i] : tiny);
      }
      for (const auto& [a, b] : edges) raw.add_edge(static_cast<int>(a), static_cast<int>(b));
    }, /*reuse_freed=*/false);
    if (!error.empty())
      throw AlgorithmError("the mean-curvature-flow skeleton failed (" + error + "); pass a skeleton with --skeleton");
    if (empty) throw AlgorithmError("the mean-curvature-flow skeleton is empty; pass a skeleton with --skeleton");
    r.raw_nodes = raw.num_nodes();
    r.raw_edges = raw.num_edges();
  }
  Skeleton result = raw;
  if (options.clean) {
    StageScope stage(options.progress, "skeleton clean-up");
    result = clean_skeleton(raw, options.clean_options, &r.clean);
  }
  if (options.progress)
    options.progress->info("skeleton: " + std::to_string(r.raw_nodes) + " nodes from the flow, " +
                           std::to_string(result.num_nodes()) + " after clean-up (" +
                           std::to_string(r.clean.branches_collapsed) + " branches collapsed, " +
                           std::to_string(r.clean.branches_pruned) + " pruned, " +
                           std::to_string(r.clean.nodes_dropped) + " redundant nodes dropped)");
  if (report) *report = r;
  return result;
}

}  // namespace subfab
