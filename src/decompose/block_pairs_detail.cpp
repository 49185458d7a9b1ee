// SPDX-License-Identifier: GPL-3.0-or-later
#include "decompose/block_pairs_detail.h"

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include "geometry/deterministic_arena.h"
#include "subfab/validate/validate_decomposition.h"
#include "validate/validate_booleans.h"

namespace subfab::detail {

namespace PMP = CGAL::Polygon_mesh_processing;

std::vector<BoundingBox> block_boxes(const std::vector<Block>& blocks) {
  std::vector<BoundingBox> boxes(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) boxes[i] = bounding_box(blocks[i].mesh);
  return boxes;
}

std::vector<double> block_volumes(const std::vector<Block>& blocks) {
  std::vector<double> volumes(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) volumes[i] = signed_volume(blocks[i].mesh);
  return volumes;
}

bool within_limits(const BoundingBox& box, Axis axis, double max_height, const Vec3& machine_size) {
  const Vec3 size = box.size();
  const int k = axis_dimension(axis);
  const double h = size[k];
  const double a = size[(k + 1) % 3], b = size[(k + 2) % 3];
  if (h > max_height || h > machine_size.z()) return false;
  return (a <= machine_size.x() && b <= machine_size.y()) || (a <= machine_size.y() && b <= machine_size.x());
}

bool overlaps_a_block(const Mesh& m, const std::vector<Block>& blocks, const std::vector<BoundingBox>& boxes,
                      const std::vector<double>& volumes, const std::function<bool(std::size_t)>& skip,
                      double tolerance, const AddedFill* added) {
  const BoundingBox box = bounding_box(m);
  const double volume = signed_volume(m);
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    if ((skip && skip(k)) || !interiors_meet(box, boxes[k])) continue;
    const double allowed = tolerance * std::min(volume, volumes[k]);
    BoundingBox region;
    if (added) {
      extend_by_fill_boxes(*added->tiles, boxes[k], region);
      if (region.is_empty()) continue;  // the fill does not reach block k
    }
    if (overlap_volume_bound(m, blocks[k].mesh, Eigen::Matrix3d::Identity()) <= allowed) continue;
    if (added) {
      const SolidIndex* index = added->index_of(k);
      if (index && (fill_misses_solid(*added->tiles, *index, boxes[k]) ||
                    fill_misses_solid(*added->columns, *index, boxes[k])))
        continue;
    }
    try {
      const double overlap = added ? exact_blocks_overlap(m, blocks[k].mesh, region) : exact_blocks_overlap(m, blocks[k].mesh);
      if (overlap > allowed) return true;
    } catch (const std::exception&) {
      return true;
    }
  }
  return false;
}

void extend_by_fill_boxes(const std::vector<BoundingBox>& fill, const BoundingBox& other, BoundingBox& region) {
  for (const BoundingBox& b : fill)
    if (interiors_meet(b, other)) {
      region.extend(b.min.cwiseMax(other.min));
      region.extend(b.max.cwiseMin(other.max));
    }
}

BoundingBox fill_hull(const std::vector<BoundingBox>& fill, const BoundingBox& block) {
  BoundingBox w;
  for (const BoundingBox& b : fill) {
    w.extend(b.min);
    w.extend(b.max);
  }
  const double margin = 1e-3 * std::max(w.diagonal(), block.diagonal());
  w.min.array() -= margin;
  w.max.array() += margin;
  return w;
}

std::unique_ptr<SolidIndex> inside_test_index(const Mesh& block) {
  if (!boolean_input_defect(block, /*whole_surface=*/true).empty()) return nullptr;
  return std::make_unique<SolidIndex>(block);
}

bool fill_misses_solid(const std::vector<BoundingBox>& fill, const SolidIndex& index, const BoundingBox& solid_box) {
  for (const BoundingBox& b : fill) {
    if (!interiors_meet(b, solid_box)) continue;
    Box3 open;
    open.min = b.min.cwiseMax(solid_box.min);
    open.max = b.max.cwiseMin(solid_box.max);
    // no face crosses the open box: it lies all inside or all outside, as
    // the point just inside its min corner (is_inside()'s perturbation)
    if (index.any_face_meets_open_box(open) || index.is_inside(open.min)) return false;
  }
  return true;
}

std::optional<Mesh> exact_block_union(const std::vector<const Mesh*>& meshes,
                                      const std::function<bool(const ExactMesh&)>& accept, RoundingReport& rounding) {
  if (meshes.empty()) return std::nullopt;
  for (const Mesh* m : meshes)
    if (count_degenerate_faces(*m) > 0) return std::nullopt;
  warm_up_exact_booleans();
  std::optional<Mesh> out;
  const std::string error = run_in_arena([&] {
    ExactMesh u = to_exact(*meshes[0]);
    const auto np = CGAL::parameters::throw_on_self_intersection(true);
    // The others joined in order, except that a union touching itself at a
    // point (two vertices at one exact point: CGAL splits the pinch) is
    // never given to the corefinement again: CGAL 5.5 can loop for ever on
    // one (remove_slivers.cpp, union_surface.cpp). Such a union waits, and
    // the next mesh is tried first; the union is given up when every mesh
    // left pinches it (unless it is the last step: the connected-components
    // test below then refuses a pinched result). Likewise a union CGAL
    // outputs as an invalid polygon mesh (decimated_knight.off at the
    // default: sliver 11 united with one neighbour gave one, and the union
    // with the second never returned, in CGAL's constrained triangulation;
    // a build with CGAL's preconditions stops there on is_valid_polygon_mesh).
    // Where every order gives one, the group is refused.
    std::vector<std::size_t> left;
    for (std::size_t k = 1; k < meshes.size(); ++k) left.push_back(k);
    while (!left.empty()) {
      bool joined = false;
      for (std::size_t i = 0; i < left.size() && !joined; ++i) {
        ExactMesh a = u, e = to_exact(*meshes[left[i]]), r;
        if (!PMP::corefine_and_compute_union(a, e, r, np, np)) continue;
        if (left.size() > 1 && (has_coincident_vertices(r) || !CGAL::is_valid_polygon_mesh(r))) continue;
        u = std::move(r);
        left.erase(left.begin() + static_cast<std::ptrdiff_t>(i));
        joined = true;
      }
      if (!joined) return;
    }
    if (u.number_of_faces() > 0 && CGAL::is_valid_polygon_mesh(u)) {
      auto fcc = u.add_property_map<ExactMesh::Face_index, std::size_t>("f:cc", 0).first;
      if ((!accept || accept(u)) && PMP::connected_components(u, fcc) == 1) {
        SuspendArena heap;
        out = to_double(u, &rounding);
      }
    }
  });
  if (!error.empty()) out.reset();  // an exact boolean that fails means: do not merge these blocks
  return out;
}

std::optional<Mesh> exact_block_union(const Mesh& a, const Mesh& b,
                                      const std::function<bool(const ExactMesh&)>& accept, RoundingReport& rounding) {
  return exact_block_union(std::vector<const Mesh*>{&a, &b}, accept, rounding);
}

}  // namespace subfab::detail
