// SPDX-License-Identifier: GPL-3.0-or-later
//! Steps 1-4 of repair_mesh(), on the triangle soup: merge vertices, drop
//! faces with a repeated corner and duplicate faces, orient consistently
//! (splitting non-manifold vertices and edges), build the halfedge mesh.
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

#include "repair/repair_steps.h"
#include "subfab/core/error.h"

namespace subfab::detail {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {
using Key = std::array<double, 3>;
Key key_of(const RepairPoint& p) { return {p.x(), p.y(), p.z()}; }

Vec3 triangle_centroid(const RepairSoup& soup, const std::array<std::size_t, 3>& t) {
  return (to_vec3(soup.points[t[0]]) + to_vec3(soup.points[t[1]]) + to_vec3(soup.points[t[2]])) / 3.0;
}
}  // namespace

Vec3 to_vec3(const RepairPoint& p) { return {p.x(), p.y(), p.z()}; }

std::string position_text(const Vec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.4g, %.4g, %.4g)", p.x(), p.y(), p.z());
  return buf;
}

MeshRepairStep merge_duplicate_vertices(RepairSoup& soup) {
  MeshRepairStep step = new_step("merge_vertices");
  std::map<Key, std::size_t> first;  // position -> new id
  std::vector<std::size_t> remap(soup.points.size());
  std::vector<RepairPoint> kept;
  kept.reserve(soup.points.size());
  for (std::size_t v = 0; v < soup.points.size(); ++v) {
    const auto [it, inserted] = first.emplace(key_of(soup.points[v]), kept.size());
    if (inserted) {
      kept.push_back(soup.points[v]);
    } else if (step.num_found++ == 0) {
      step.where = to_vec3(soup.points[v]);
    }
    remap[v] = it->second;
  }
  for (auto& t : soup.triangles)
    for (auto& v : t) v = remap[v];
  soup.points = std::move(kept);
  step.message = step_message(step, " vertices at the same position as another merged (e.g. at ",
                              "no two vertices at the same position");
  return step;
}

MeshRepairStep remove_repeated_corner_faces(RepairSoup& soup) {
  MeshRepairStep step = new_step("repeated_corner_faces");
  std::vector<std::array<std::size_t, 3>> kept;
  kept.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles) {
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) {
      kept.push_back(t);
    } else if (step.num_found++ == 0) {
      step.where = triangle_centroid(soup, t);
    }
  }
  step.num_faces_removed = step.num_found;
  soup.triangles = std::move(kept);
  step.message = step_message(
      step, " faces with a repeated corner (zero area, after merging) removed (e.g. at ",
      "no face with a repeated corner");
  return step;
}

MeshRepairStep remove_duplicate_faces(RepairSoup& soup) {
  MeshRepairStep step = new_step("duplicate_faces");
  std::map<std::array<std::size_t, 3>, std::size_t> seen;
  std::vector<std::array<std::size_t, 3>> kept;
  kept.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles) {
    std::array<std::size_t, 3> sorted = t;
    std::sort(sorted.begin(), sorted.end());
    if (seen.emplace(sorted, kept.size()).second) {
      kept.push_back(t);
    } else if (step.num_found++ == 0) {
      step.where = triangle_centroid(soup, t);
    }
  }
  step.num_faces_removed = step.num_found;
  soup.triangles = std::move(kept);
  step.message = step_message(step,
                              " faces on the same three vertices as another (either orientation) "
                              "removed, one kept (e.g. at ",
                              "no duplicate face");
  return step;
}

std::vector<MeshRepairStep> orient_soup(RepairSoup& soup, RepairSurface& mesh, SoupState state) {
  MeshRepairStep split = new_step("split_non_manifold");
  MeshRepairStep orient = new_step("orient");
  const std::size_t n0 = soup.points.size();
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles) polygons.push_back({t[0], t[1], t[2]});
  if (state == SoupState::ManifoldConsistent) {
    split.message = "no pinched vertex, no edge shared by more than two faces";
    orient.message = "neighbouring faces already agree in orientation";
    mesh.clear();
    PMP::polygon_soup_to_polygon_mesh(soup.points, polygons, mesh);
    return {split, orient};
  }
  PMP::orient_polygon_soup(soup.points, polygons);
  // Copies made for non-manifold vertices are appended: map them back to
  // their original (same position) to tell a flip from a renumbering.
  std::map<Key, std::size_t> original;
  for (std::size_t v = 0; v < n0; ++v) original.emplace(key_of(soup.points[v]), v);
  std::vector<std::size_t> origin(soup.points.size());
  for (std::size_t v = 0; v < soup.points.size(); ++v)
    origin[v] = v < n0 ? v : original.at(key_of(soup.points[v]));
  split.num_found = soup.points.size() - n0;
  if (split.applied()) split.where = to_vec3(soup.points[n0]);
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& before = soup.triangles[f];
    const auto& after = polygons[f];
    bool same = false;
    for (int r = 0; r < 3 && !same; ++r)
      same = origin[after[0]] == before[static_cast<std::size_t>(r)] &&
             origin[after[1]] == before[static_cast<std::size_t>((r + 1) % 3)];
    if (!same && orient.num_found++ == 0) orient.where = triangle_centroid(soup, before);
  }
  for (std::size_t f = 0; f < polygons.size(); ++f)
    soup.triangles[f] = {polygons[f][0], polygons[f][1], polygons[f][2]};
  split.message = step_message(split,
                               " vertex copies made to split pinched vertices and edges shared by "
                               "more than two faces into one per fan (e.g. at ",
                               "no pinched vertex, no edge shared by more than two faces");
  orient.message = step_message(orient, " faces flipped to agree with their neighbours (e.g. at ",
                                "neighbouring faces already agree in orientation");
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons))
    throw InvalidMeshError("the faces cannot be made into a manifold surface even after splitting non-manifold "
                           "vertices; repair the mesh in a mesh editor");
  mesh.clear();
  PMP::polygon_soup_to_polygon_mesh(soup.points, polygons, mesh);
  return {split, orient};
}

}  // namespace subfab::detail
