// SPDX-License-Identifier: GPL-3.0-or-later
//! Steps 11-12 of repair_mesh(): resolve self-intersections (autorefine and
//! keep the outer hull, else cut out the crossing region and close it with
//! faired patches, else local remeshing), then orient every shell to bound a
//! volume.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Random.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/repair_self_intersections.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>

#include <exception>
#include <set>
#include <iterator>

#include "repair/repair_steps.h"
#include "subfab/core/error.h"

namespace subfab::detail {

namespace PMP = CGAL::Polygon_mesh_processing;
using Face = RepairSurface::Face_index;
using Vertex = RepairSurface::Vertex_index;

namespace {

//! Vertex rings around the crossing faces that the first excision round cuts
//! out (one more each round): 2 resolves gentildonna.obj in 3 rounds and leaves
//! no crease there that the decomposition cannot mill.
constexpr std::size_t kExcisionRings = 2;
//! Crossing faces within this many face rings of each other belong to one
//! fold of the surface (cut out); farther apart, to two parts that overlap
//! (autorefined, outer hull kept).
constexpr std::size_t kFoldRings = 8;

std::vector<std::pair<Face, Face>> intersecting_pairs(const RepairSurface& mesh) {
  std::vector<std::pair<Face, Face>> pairs;
  PMP::self_intersections<CGAL::Sequential_tag>(mesh, std::back_inserter(pairs));
  return pairs;
}

//! Reverses every closed piece whose signed volume is negative, so that each
//! piece, seen alone, is outward: what the autorefinement's rule (keep the
//! patches on the outside of every other piece) expects.
void orient_pieces_by_volume(RepairSurface& mesh) {
  auto map = mesh.add_property_map<Face, std::size_t>("f:repair_cc", 0).first;
  const std::size_t n = PMP::connected_components(mesh, map);
  std::vector<double> volume(n, 0.0);
  std::vector<std::vector<Face>> faces(n);
  for (Face f : mesh.faces()) {
    std::array<Vec3, 3> p;
    int k = 0;
    for (Vertex v : mesh.vertices_around_face(mesh.halfedge(f))) p[static_cast<std::size_t>(k++)] = to_vec3(mesh.point(v));
    volume[map[f]] += p[0].dot(p[1].cross(p[2])) / 6.0;
    faces[map[f]].push_back(f);
  }
  for (std::size_t c = 0; c < n; ++c)
    if (volume[c] < 0) PMP::reverse_face_orientations(faces[c], mesh);
  mesh.remove_property_map(map);
}

//! The bounding box of a mesh's vertices.
BoundingBox box_of(const RepairSurface& mesh) {
  BoundingBox box;
  for (Vertex v : mesh.vertices()) box.extend(to_vec3(mesh.point(v)));
  return box;
}

//! A sanity gate on the outer-hull rule: it assumes overlapping closed
//! shells; on a single sheet folded through itself it can drop most of the
//! surface (cow.obj: 5804 faces -> 10). Such a result is refused (then the
//! local repair is tried): it must keep 90% of the bbox diagonal and a
//! quarter of the area.
bool keeps_the_shape(const RepairSurface& before, const RepairSurface& after) {
  return !after.is_empty() && box_of(after).diagonal() >= 0.9 * box_of(before).diagonal() &&
         PMP::area(after) >= 0.25 * PMP::area(before);
}

//! One autorefine round on an exact copy (exact constructions: with double
//! coordinates CGAL 5.5's output builder leaves faces with two corners at the
//! same rounded intersection point), rounded back to doubles. `mesh` is
//! replaced when the rounded copy is closed; true when it is also free of
//! self-intersections (rounding the new points can leave tiny crossings,
//! which the next round resolves).
bool autorefine_round(RepairSurface& mesh, bool& replaced) {
  using ExactSurface = CGAL::Surface_mesh<CGAL::Exact_predicates_exact_constructions_kernel::Point_3>;
  ExactSurface exact;
  CGAL::copy_face_graph(mesh, exact);
  try {
    PMP::experimental::autorefine_and_remove_self_intersections(exact);
  } catch (const std::exception& e) {
    return false;  // CGAL refuses some configurations (e.g. coplanar overlaps): try the local repair
  }
  exact.collect_garbage();
  RepairSurface copy;
  CGAL::copy_face_graph(exact, copy);
  if (!keeps_the_shape(mesh, copy)) return false;
  if (copy.is_empty() || !CGAL::is_closed(copy)) return false;
  mesh = std::move(copy);
  replaced = true;
  return !PMP::does_self_intersect(mesh);
}

//! True when face g is within `rings` face rings of face f (faces sharing a
//! vertex with f are ring 1): the two faces of a crossing pair belong to one
//! fold of the surface rather than to two parts that overlap.
bool within_rings(const RepairSurface& mesh, Face f, Face g, std::size_t rings) {
  std::set<Face> seen{f};
  std::vector<Face> front{f};
  for (std::size_t r = 0; r < rings && !front.empty(); ++r) {
    std::vector<Face> next;
    for (Face h : front)
      for (Vertex v : mesh.vertices_around_face(mesh.halfedge(h)))
        for (Face k : mesh.faces_around_target(mesh.halfedge(v)))
          if (k != RepairSurface::null_face() && seen.insert(k).second) {
            if (k == g) return true;
            next.push_back(k);
          }
    front = std::move(next);
  }
  return false;
}

//! One excision round: the faces that cross, and every face within `rings`
//! vertex rings of them, are removed and the holes left closed by refined,
//! faired patches (fill_holes, step 8). Made for a surface crumpled or folded
//! through itself (gentildonna.obj: tiny folds whose crossing faces also make
//! creases no milling axis sees; cow.obj's folds at the horns and the muzzle
//! tip), where the outer-hull rule does not apply and local
//! remeshing keeps the crumple. With `fold_rings` > 0, only the pairs within
//! that many face rings of each other are cut out (the folds). Same contract
//! as autorefine_round; the number of holes closed is added to `holes` when
//! `mesh` is replaced.
bool excise_round(RepairSurface& mesh, std::size_t rings, std::size_t& holes, std::size_t fold_rings = 0) {
  std::set<Vertex> region;
  for (const auto& [f, g] : intersecting_pairs(mesh))
    if (fold_rings == 0 || within_rings(mesh, f, g, fold_rings))
    for (Face h : {f, g})
      for (Vertex v : mesh.vertices_around_face(mesh.halfedge(h))) region.insert(v);
  for (std::size_t r = 0; r < rings; ++r) {
    std::set<Vertex> grown = region;
    for (Vertex v : region)
      for (Vertex w : mesh.vertices_around_target(mesh.halfedge(v))) grown.insert(w);
    region = std::move(grown);
  }
  std::set<Face> cut;
  for (Vertex v : region)
    for (Face f : mesh.faces_around_target(mesh.halfedge(v)))
      if (f != RepairSurface::null_face()) cut.insert(f);
  RepairSurface copy = mesh;
  for (Face f : cut) CGAL::Euler::remove_face(copy.halfedge(f), copy);
  copy.collect_garbage();
  std::size_t closed = 0;
  try {
    split_pinched_vertices(copy);  // a cut through a vertex leaves two fans there
    closed = fill_holes(copy).num_found;
  } catch (const InvalidMeshError&) {
    return false;  // a hole that cannot be closed
  }
  if (!keeps_the_shape(mesh, copy) || !CGAL::is_closed(copy)) return false;
  holes += closed;
  mesh = std::move(copy);
  return !PMP::does_self_intersect(mesh);
}

//! One local-remeshing round restricted to the faces that intersect (same
//! contract as autorefine_round).
bool local_round(RepairSurface& mesh) {
  std::set<Face> involved;
  for (const auto& [f, g] : intersecting_pairs(mesh)) {
    involved.insert(f);
    involved.insert(g);
  }
  RepairSurface copy = mesh;
  // CGAL's local repair draws from its process-wide default generator:
  // reseed it so that every call gives the same result.
  CGAL::get_default_random() = CGAL::Random(0);
  try {
    PMP::experimental::remove_self_intersections(involved, copy);
  } catch (const std::exception&) {
    return false;
  }
  copy.collect_garbage();
  if (!keeps_the_shape(mesh, copy) || !CGAL::is_closed(copy)) return false;
  mesh = std::move(copy);
  return !PMP::does_self_intersect(mesh);
}

}  // namespace

MeshRepairStep resolve_self_intersections(RepairSurface& mesh, std::size_t max_rounds,
                                          const std::vector<Face>* candidates) {
  MeshRepairStep step = new_step("self_intersections");
  std::vector<std::pair<Face, Face>> pairs;
  if (candidates)
    PMP::self_intersections<CGAL::Sequential_tag>(*candidates, mesh, std::back_inserter(pairs));
  else
    pairs = intersecting_pairs(mesh);
  step.num_found = pairs.size();
  if (pairs.empty()) {
    step.message = "no two faces intersect";
    return step;
  }
  step.where = face_centroid(mesh, pairs.front().first);
  const std::size_t before = mesh.number_of_faces();
  orient_pieces_by_volume(mesh);
  std::string how;
  bool autorefined = false;
  for (std::size_t round = 0; round < max_rounds && how.empty(); ++round)
    if (autorefine_round(mesh, autorefined)) how = "autorefined; the patches inside another part dropped (outer hull kept)";
  std::size_t holes = 0;
  // Where folds and overlapping parts both cross (cow.obj: small folds at
  // the horns and the muzzle tip, and the muzzle pushed into the head;
  // cutting out everything drops the muzzle tip: 0.091 of the diagonal), the
  // folds are cut out first, with as few rings as resolve them, then the
  // overlap autorefined (outer hull kept).
  // Only when the autorefinement was refused outright: after an accepted
  // one, the crossings left come from rounding its new points (two
  // overlapping cubes), which the local remeshing below resolves.
  std::size_t num_folds = 0;
  if (how.empty() && !autorefined)
    for (const auto& [f, g] : pairs) num_folds += within_rings(mesh, f, g, kFoldRings) ? 1 : 0;
  for (std::size_t rings = 0; rings <= kExcisionRings && how.empty() && num_folds > 0 && num_folds < pairs.size();
       ++rings) {
    RepairSurface copy = mesh;
    std::size_t fold_holes = 0;
    bool resolved = excise_round(copy, rings, fold_holes, kFoldRings);
    bool refined = false;
    for (std::size_t round = 0; round < max_rounds && !resolved && fold_holes > 0; ++round)
      resolved = autorefine_round(copy, refined);
    if (resolved && fold_holes > 0) {
      mesh = std::move(copy);
      how = "the crossing faces of " + std::to_string(num_folds) + " pairs in folds (within " +
            std::to_string(kFoldRings) + " rings of each other)" +
            (rings ? " and " + std::to_string(rings) + " rings of faces around them" : std::string()) +
            " cut out and the " + std::to_string(fold_holes) + " holes closed by faired patches" +
            (refined ? ", then the overlapping parts autorefined (outer hull kept)" : "");
    }
  }
  for (std::size_t round = 0; round < max_rounds && how.empty(); ++round)
    if (excise_round(mesh, kExcisionRings + round, holes))
      how = std::string(autorefined ? "autorefined (outer hull kept), then " : "") +
            "the crossing faces and " + std::to_string(kExcisionRings + round) +
            " rings of faces around them cut out and the " + std::to_string(holes) +
            " holes closed by faired patches";
  if (how.empty() && local_round(mesh))
    how = autorefined ? "autorefined (outer hull kept), then the crossings left by rounding the new points to doubles "
                        "remeshed locally (PMP::experimental::remove_self_intersections)"
                      : "remeshed locally (PMP::experimental::remove_self_intersections)";
  if (how.empty()) {
    const auto left = intersecting_pairs(mesh);
    throw InvalidMeshError("the surface intersects itself and the repair could not resolve it: " +
                           std::to_string(pairs.size()) + " pairs of faces intersect, e.g. at " +
                           position_text(*step.where) +
                           " (neither autorefinement, nor cutting out the crossing region and closing it, nor local remeshing gave a closed surface without "
                           "self-intersections" +
                           (left.empty() ? std::string() : ", " + std::to_string(left.size()) + " pairs left") +
                           "); remove them in a mesh editor (e.g. a boolean union of the overlapping parts)");
  }
  step.num_faces_removed = before;
  step.num_faces_added = mesh.number_of_faces();
  step.message = std::to_string(pairs.size()) + " pairs of intersecting faces (e.g. at " +
                 position_text(*step.where) + ") " + how + ": " + std::to_string(before) + " faces -> " +
                 std::to_string(mesh.number_of_faces());
  return step;
}

MeshRepairStep orient_outward(RepairSurface& mesh) {
  MeshRepairStep step = new_step("orient_outward");
  std::vector<Vertex> first(mesh.number_of_faces() + mesh.number_of_removed_faces());
  std::vector<Vertex> second(first.size());
  for (Face f : mesh.faces()) {
    first[f.idx()] = mesh.source(mesh.halfedge(f));
    second[f.idx()] = mesh.target(mesh.halfedge(f));
  }
  PMP::orient_to_bound_a_volume(mesh);
  for (Face f : mesh.faces()) {
    bool same = false;
    for (auto h : mesh.halfedges_around_face(mesh.halfedge(f)))
      same = same || (mesh.source(h) == first[f.idx()] && mesh.target(h) == second[f.idx()]);
    if (!same && step.num_found++ == 0) step.where = face_centroid(mesh, f);
  }
  step.message = step_message(step,
                              " faces flipped so that every shell bounds the volume (outer shells "
                              "outward, cavities inward; e.g. at ",
                              "every shell already bounds the volume");
  return step;
}

}  // namespace subfab::detail
