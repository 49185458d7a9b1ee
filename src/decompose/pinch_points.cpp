// SPDX-License-Identifier: GPL-3.0-or-later
// Pinch points of carved pieces and the axis-aligned cuts through them
// (thesis Section 4.3.3, carving), see pinch_points.h.
#include "decompose/pinch_points.h"

#include <CGAL/Polygon_mesh_processing/connected_components.h>

#include <algorithm>
#include <map>

namespace subfab::detail {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using FT = ExactKernel::FT;

}  // namespace

bool is_cut(const Cuts& cuts, int k, double v) {
  const auto& c = cuts[static_cast<std::size_t>(k)];
  return std::binary_search(c.begin(), c.end(), v);
}

std::vector<ExactPoint> pinch_points(ExactMesh& mesh) {
  std::vector<ExactPoint> out;
  if (mesh.number_of_faces() == 0) return out;
  auto fcc = mesh.add_property_map<FaceIndex, std::size_t>("f:pinch_cc", 0).first;
  PMP::connected_components(mesh, fcc);
  std::map<ExactPoint, std::vector<std::size_t>, ExactPointLess> components_at;
  for (VertexIndex v : mesh.vertices()) {
    if (mesh.is_isolated(v)) continue;
    HalfedgeIndex h = mesh.halfedge(v);
    if (mesh.is_border(h)) h = mesh.opposite(h);
    std::vector<std::size_t>& at = components_at[mesh.point(v)];
    const std::size_t c = fcc[mesh.face(h)];
    if (std::find(at.begin(), at.end(), c) != at.end())
      out.push_back(mesh.point(v));
    else
      at.push_back(c);
  }
  mesh.remove_property_map(fcc);
  std::sort(out.begin(), out.end(), ExactPointLess());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<ExactPoint> contact_points(const ExactMesh& mesh, const ExactPoint& p) {
  std::map<ExactPoint, std::vector<VertexIndex>, ExactPointLess> ends;  // far end -> vertices at p
  for (VertexIndex v : mesh.vertices()) {
    if (mesh.is_isolated(v) || mesh.point(v) != p) continue;
    for (HalfedgeIndex h : CGAL::halfedges_around_target(mesh.halfedge(v), mesh)) {
      auto& at = ends[mesh.point(mesh.source(h))];
      if (std::find(at.begin(), at.end(), v) == at.end()) at.push_back(v);
    }
  }
  std::vector<ExactPoint> out{p};
  for (const auto& [q, at] : ends)
    if (at.size() > 1) out.push_back(q);
  return out;
}

bool on_box_face(const ExactPoint& p, const Box3& b, int k) {
  if (p[k] != FT(b.min[k]) && p[k] != FT(b.max[k])) return false;
  for (int j = 0; j < 3; ++j)
    if (j != k && (p[j] < FT(b.min[j]) || p[j] > FT(b.max[j]))) return false;
  return true;
}

bool add_pinch_cuts(const std::vector<ExactPoint>& pinches, const Box3& box, const std::vector<Box3>& holes,
                    Cuts& cuts, std::size_t& num_added) {
  bool added = false;
  for (const ExactPoint& p : pinches)
    for (int k = 0; k < 3; ++k) {
      const double v = CGAL::to_double(CGAL::exact(p[k]));
      if (FT(v) != p[k] || !(v > box.min[k] && v < box.max[k]) || is_cut(cuts, k, v)) continue;
      if (std::any_of(holes.begin(), holes.end(), [&](const Box3& h) { return on_box_face(p, h, k); })) continue;
      auto& c = cuts[static_cast<std::size_t>(k)];
      c.insert(std::upper_bound(c.begin(), c.end(), v), v);
      added = true;
      ++num_added;
      break;
    }
  return added;
}

}  // namespace subfab::detail
