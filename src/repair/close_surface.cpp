// SPDX-License-Identifier: GPL-3.0-or-later
//! Steps 5-10 of repair_mesh(), on the halfedge mesh: stitch borders, remove
//! small pieces, remove zero-area faces, fill holes with faired patches,
//! remove pieces that enclose no volume, separate split pinches.
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <set>

#include "repair/repair_steps.h"
#include "subfab/core/error.h"

namespace subfab::detail {

namespace PMP = CGAL::Polygon_mesh_processing;
using Face = RepairSurface::Face_index;
using Vertex = RepairSurface::Vertex_index;
using Halfedge = RepairSurface::Halfedge_index;

namespace {

//! Connected components of `mesh` (faces linked by edges): component id per face.
std::size_t components(const RepairSurface& mesh, std::vector<std::size_t>& id_of_face_index,
                       RepairSurface::Property_map<Face, std::size_t>& map) {
  const std::size_t n = PMP::connected_components(mesh, map);
  id_of_face_index.assign(mesh.number_of_faces() + mesh.number_of_removed_faces(), 0);
  for (Face f : mesh.faces()) id_of_face_index[f.idx()] = map[f];
  return n;
}

//! Removes the faces of the listed components (and vertices left alone).
void remove_components(RepairSurface& mesh, const std::vector<std::size_t>& ids,
                       RepairSurface::Property_map<Face, std::size_t>& map) {
  if (ids.empty()) return;
  PMP::remove_connected_components(mesh, ids, map);
  mesh.collect_garbage();
}

//! True when the boundary cycle through `h` lies in one plane (every vertex
//! within 1e-9 x the cycle's bbox diagonal of the plane through its centroid
//! with the cycle's Newell normal).
bool is_planar(const RepairSurface& mesh, Halfedge h) {
  std::vector<Vec3> p;
  for (Halfedge g : mesh.halfedges_around_face(h)) p.push_back(to_vec3(mesh.point(mesh.target(g))));
  Vec3 normal = Vec3::Zero(), centroid = Vec3::Zero();
  BoundingBox box;
  for (std::size_t i = 0; i < p.size(); ++i) {
    normal += p[i].cross(p[(i + 1) % p.size()]);
    centroid += p[i];
    box.extend(p[i]);
  }
  if (!(normal.norm() > 0)) return false;
  centroid /= static_cast<double>(p.size());
  normal.normalize();
  for (const Vec3& q : p)
    if (std::abs((q - centroid).dot(normal)) > 1e-9 * box.diagonal()) return false;
  return true;
}

}  // namespace

Vec3 face_centroid(const RepairSurface& mesh, Face f) {
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (Vertex v : mesh.vertices_around_face(mesh.halfedge(f))) {
    sum += to_vec3(mesh.point(v));
    ++n;
  }
  return n ? Vec3(sum / n) : sum;
}

MeshRepairStep stitch_borders(RepairSurface& mesh) {
  MeshRepairStep step = new_step("stitch");
  // An example: a border edge with the same end positions as another.
  std::map<std::array<double, 6>, int> border_edges;
  for (Halfedge h : mesh.halfedges()) {
    if (!mesh.is_border(h)) continue;
    Vec3 a = to_vec3(mesh.point(mesh.source(h))), b = to_vec3(mesh.point(mesh.target(h)));
    if (std::lexicographical_compare(b.data(), b.data() + 3, a.data(), a.data() + 3)) std::swap(a, b);
    if (++border_edges[{a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}] == 2 && !step.where) step.where = (a + b) / 2;
  }
  const std::size_t faces_before = mesh.number_of_faces();
  step.num_found = PMP::stitch_borders(mesh);
  mesh.collect_garbage();
  if (!step.applied()) step.where.reset();
  step.num_faces_removed = faces_before - mesh.number_of_faces();
  step.message = step_message(
      step, " pairs of border edges with the same end positions sewn together (e.g. at ",
      "no border edges to sew together");
  return step;
}

MeshRepairStep remove_small_components(RepairSurface& mesh, double min_fraction) {
  MeshRepairStep step = new_step("small_components");
  auto map = mesh.add_property_map<Face, std::size_t>("f:repair_cc", 0).first;
  std::vector<std::size_t> id;
  const std::size_t n = components(mesh, id, map);
  std::vector<BoundingBox> box(n);
  std::vector<std::size_t> num_faces(n, 0);
  for (Face f : mesh.faces()) {
    ++num_faces[map[f]];
    for (Vertex v : mesh.vertices_around_face(mesh.halfedge(f))) box[map[f]].extend(to_vec3(mesh.point(v)));
  }
  double largest = 0;
  for (const auto& b : box) largest = std::max(largest, b.diagonal());
  std::vector<std::size_t> remove;
  for (std::size_t c = 0; c < n; ++c)
    if (box[c].diagonal() < min_fraction * largest) {
      remove.push_back(c);
      if (!step.where) step.where = (box[c].min + box[c].max) / 2;
      step.num_faces_removed += num_faces[c];
    }
  step.num_found = remove.size();
  remove_components(mesh, remove, map);
  mesh.remove_property_map(map);
  step.message = step_message(step,
                              " of " + std::to_string(n) + " pieces smaller than " +
                                  std::to_string(min_fraction) +
                                  " x the largest piece's bbox diagonal removed (" +
                                  std::to_string(step.num_faces_removed) + " faces; e.g. at ",
                              std::to_string(n) + (n == 1 ? " piece" : " pieces") + ", none small");
  return step;
}

MeshRepairStep remove_zero_area_faces(RepairSurface& mesh) {
  MeshRepairStep step = new_step("zero_area_faces");
  std::vector<Face> degenerate;
  PMP::degenerate_faces(mesh, std::back_inserter(degenerate));
  step.num_found = degenerate.size();
  if (!step.applied()) {
    step.message = "no face with collinear corners";
    return step;
  }
  step.where = face_centroid(mesh, degenerate.front());
  const std::size_t before = mesh.number_of_faces();
  const bool all = PMP::remove_degenerate_faces(mesh);
  mesh.collect_garbage();
  step.num_faces_removed = before > mesh.number_of_faces() ? before - mesh.number_of_faces() : 0;
  std::vector<Face> left;
  PMP::degenerate_faces(mesh, std::back_inserter(left));
  step.message = std::to_string(step.num_found) + " zero-area faces (collinear corners) removed by edge collapses and "
                 "flips (e.g. at " + position_text(*step.where) + ")";
  if (!all || !left.empty())
    throw InvalidMeshError(std::to_string(left.size()) + " zero-area faces (collinear corners) could not be removed, "
                           "e.g. at " + position_text(left.empty() ? *step.where : face_centroid(mesh, left.front())) +
                           "; remove them in a mesh editor");
  return step;
}

MeshRepairStep fill_holes(RepairSurface& mesh) {
  MeshRepairStep step = new_step("fill_holes");
  std::vector<Halfedge> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  step.num_found = cycles.size();
  std::size_t not_faired = 0, largest = 0, num_planar = 0;
  for (Halfedge h : cycles) {
    std::size_t length = 0;
    for (Halfedge g : mesh.halfedges_around_face(h)) {
      (void)g;
      ++length;
    }
    largest = std::max(largest, length);
    if (!step.where) step.where = to_vec3(mesh.point(mesh.target(h)));
    std::vector<Face> patch;
    std::vector<Vertex> inner;
    bool faired = true;
    if (is_planar(mesh, h)) {
      ++num_planar;  // fairing would bulge a flat side (C1 to its neighbours); a flat refined patch is exact
      PMP::triangulate_and_refine_hole(mesh, h, std::back_inserter(patch), std::back_inserter(inner));
    } else {
      faired = std::get<0>(
          PMP::triangulate_refine_and_fair_hole(mesh, h, std::back_inserter(patch), std::back_inserter(inner)));
    }
    if (patch.empty())
      throw InvalidMeshError("a hole of " + std::to_string(length) + " edges at " +
                             position_text(to_vec3(mesh.point(mesh.target(h)))) +
                             " cannot be closed; close it in a mesh editor");
    if (!faired) ++not_faired;
    step.num_faces_added += patch.size();
  }
  if (!step.applied()) {
    step.message = "closed: no hole";
    return step;
  }
  step.message = std::to_string(step.num_found) + " holes (the largest with " + std::to_string(largest) +
                 " edges; e.g. at " + position_text(*step.where) + ") closed by refined, faired patches of " +
                 std::to_string(step.num_faces_added) + " faces" +
                 (num_planar ? " (" + std::to_string(num_planar) + " planar holes closed flat)" : "") +
                 (not_faired ? " (" + std::to_string(not_faired) + " left flat: fairing had no solution)" : "");
  return step;
}

MeshRepairStep remove_flat_components(RepairSurface& mesh) {
  MeshRepairStep step = new_step("flat_components");
  auto map = mesh.add_property_map<Face, std::size_t>("f:repair_cc", 0).first;
  std::vector<std::size_t> id;
  const std::size_t n = components(mesh, id, map);
  std::vector<double> volume(n, 0.0);
  std::vector<BoundingBox> box(n);
  std::vector<std::size_t> num_faces(n, 0);
  for (Face f : mesh.faces()) {
    std::array<Vec3, 3> p;
    int k = 0;
    for (Vertex v : mesh.vertices_around_face(mesh.halfedge(f))) p[static_cast<std::size_t>(k++)] = to_vec3(mesh.point(v));
    volume[map[f]] += p[0].dot(p[1].cross(p[2])) / 6.0;
    for (const Vec3& q : p) box[map[f]].extend(q);
    ++num_faces[map[f]];
  }
  std::vector<std::size_t> remove;
  for (std::size_t c = 0; c < n; ++c) {
    const double d = box[c].diagonal();
    if (std::abs(volume[c]) <= 1e-9 * d * d * d) {
      remove.push_back(c);
      if (!step.where) step.where = (box[c].min + box[c].max) / 2;
      step.num_faces_removed += num_faces[c];
    }
  }
  step.num_found = remove.size();
  remove_components(mesh, remove, map);
  mesh.remove_property_map(map);
  step.message = step_message(step,
                              " closed pieces that enclose no volume (|volume| <= 1e-9 x bbox "
                              "diagonal^3: sheets closed onto themselves) removed (" +
                                  std::to_string(step.num_faces_removed) + " faces; e.g. at ",
                              "every piece encloses a volume");
  if (mesh.number_of_faces() == 0)
    throw InvalidMeshError("the surface encloses no volume (a sheet, or pieces that close onto themselves): there is "
                           "no solid to repair; give a mesh that bounds a volume");
  return step;
}

MeshRepairStep separate_pinches(RepairSurface& mesh, double distance) {
  MeshRepairStep step = new_step("separate_pinches");
  std::map<std::array<double, 3>, std::vector<Vertex>> at;
  for (Vertex v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    at[{p.x(), p.y(), p.z()}].push_back(v);
  }
  std::vector<std::pair<Vertex, RepairPoint>> moves;
  double largest_move = 0;
  for (const auto& [key, group] : at) {
    if (group.size() < 2) continue;
    if (!step.where) step.where = Vec3(key[0], key[1], key[2]);
    ++step.num_found;
    for (Vertex v : group) {
      const Vec3 p = to_vec3(mesh.point(v));
      Vec3 direction = Vec3::Zero();
      double shortest = std::numeric_limits<double>::infinity();
      for (Vertex w : mesh.vertices_around_target(mesh.halfedge(v))) {
        const Vec3 e = to_vec3(mesh.point(w)) - p;
        if (e.norm() > 0) direction += e / e.norm();
        shortest = std::min(shortest, e.norm());
      }
      if (!(direction.norm() > 0) || !std::isfinite(shortest)) continue;
      const double d = std::min(distance, shortest / 10);
      largest_move = std::max(largest_move, d);
      const Vec3 q = p + d * direction.normalized();
      moves.emplace_back(v, RepairPoint(q.x(), q.y(), q.z()));
    }
  }
  for (const auto& [v, q] : moves) mesh.point(v) = q;
  step.message = step_message(step,
                              " points where separate fans met (split pinched vertices or edges) "
                              "pulled apart: each copy moved up to " +
                                  std::to_string(largest_move) + " along its own fan (e.g. at ",
                              "no two vertices at the same position");
  return step;
}

MeshRepairStep split_pinched_vertices(RepairSurface& mesh) {
  MeshRepairStep step = new_step("split_non_manifold");
  std::vector<std::vector<Vertex>> copies;
  step.num_found = PMP::duplicate_non_manifold_vertices(mesh, CGAL::parameters::output_iterator(std::back_inserter(copies)));
  if (!copies.empty() && !copies.front().empty()) step.where = to_vec3(mesh.point(copies.front().front()));
  step.message = step_message(
      step,
      " pinched vertices left by the self-intersection resolution split into one per fan (e.g. at ",
      "no pinched vertex");
  return step;
}

Mesh to_plain_mesh(const RepairSurface& mesh) {
  Mesh out;
  std::vector<int> id(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), -1);
  for (Vertex v : mesh.vertices()) {
    id[v.idx()] = static_cast<int>(out.vertices.size());
    out.vertices.push_back(to_vec3(mesh.point(v)));
  }
  for (Face f : mesh.faces()) {
    Triangle t{};
    int k = 0;
    for (Vertex v : mesh.vertices_around_face(mesh.halfedge(f)))
      if (k < 3) t[static_cast<std::size_t>(k++)] = id[v.idx()];
    out.faces.push_back(t);
  }
  return out;
}

}  // namespace subfab::detail
