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

}  // namespace

Skeleton compute_skeleton(const Mesh& mesh, const ComputeSkeletonOptions& options, ComputeSkeletonReport* report) {
  ComputeSkeletonReport r;
  Skeleton raw;
  {
    StageScope stage(options.progress, "skeleton (mean curvature flow)");
    SurfaceMesh sm = to_surface_mesh(mesh);
    McfSkeleton mcf;
    Skeletonization skeletonize(sm);
    skeletonize(mcf);
    const std::size_t n = boost::num_vertices(mcf);
    if (n == 0) throw AlgorithmError("the mean-curvature-flow skeleton is empty; pass a skeleton with --skeleton");
    Tree tree(faces(sm).first, faces(sm).second, sm);
    tree.accelerate_distance_queries();
    std::vector<McfSkeleton::vertex_descriptor> order;
    for (auto v : CGAL::make_range(boost::vertices(mcf))) order.push_back(v);
    std::vector<int> index(n, -1);
    for (std::size_t i = 0; i < order.size(); ++i) {
      const auto& node = mcf[order[i]];
      const Vec3 p(node.point.x(), node.point.y(), node.point.z());
      double sum = 0;
      for (auto sv : node.vertices) {
        const Point& q = sm.point(sv);
        sum += std::sqrt(CGAL::squared_distance(node.point, q));
      }
      double radius = node.vertices.empty() ? 0.0 : sum / static_cast<double>(node.vertices.size());
      if (!(radius > 0)) radius = std::sqrt(tree.squared_distance(node.point));
      if (!(radius > 0)) radius = 1e-9 * bounding_box(mesh).diagonal();
      index[i] = raw.add_node(p, radius);
    }
    for (auto e : CGAL::make_range(boost::edges(mcf))) {
      const auto a = boost::source(e, mcf), b = boost::target(e, mcf);
      raw.add_edge(index[static_cast<std::size_t>(a)], index[static_cast<std::size_t>(b)]);
    }
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
