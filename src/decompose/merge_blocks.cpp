// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/merge_blocks.h"

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "decompose/deterministic_arena.h"
#include "decompose/exact_mesh.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/validate_decomposition.h"

namespace subfab {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using detail::ExactMesh;
using detail::ExactPoint;

bool boxes_touch(const BoundingBox& a, const BoundingBox& b) {
  return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}

//! Exact height-field test of a closed exact mesh along an axis.
bool exact_height_field(const ExactMesh& m, Axis axis) {
  const int k = axis_dimension(axis);
  const int s = axis_sign(axis);
  std::optional<detail::ExactKernel::FT> base;
  for (auto v : m.vertices()) {
    const auto h = s > 0 ? m.point(v)[k] : -m.point(v)[k];
    if (!base || h < *base) base = h;
  }
  for (auto f : m.faces()) {
    auto e = m.halfedge(f);
    const ExactPoint& a = m.point(m.source(e));
    const ExactPoint& b = m.point(m.target(e));
    const ExactPoint& c = m.point(m.target(m.next(e)));
    const auto n = CGAL::cross_product(b - a, c - a);
    const auto nd = s > 0 ? n[k] : -n[k];
    if (CGAL::sign(nd) != CGAL::NEGATIVE) continue;
    for (const ExactPoint* p : {&a, &b, &c})
      if ((s > 0 ? (*p)[k] : -(*p)[k]) != *base) return false;
  }
  return true;
}

bool within_limits(const Mesh& m, Axis axis, const MergeOptions& o) {
  const Vec3 size = bounding_box(m).size();
  const int k = axis_dimension(axis);
  const double h = size[k];
  const double a = size[(k + 1) % 3], b = size[(k + 2) % 3];
  if (h > o.max_height || h > o.machine_size.z()) return false;
  return (a <= o.machine_size.x() && b <= o.machine_size.y()) || (a <= o.machine_size.y() && b <= o.machine_size.x());
}

//! The union of two blocks if it is a valid block, computed in a private arena.
std::optional<Mesh> try_union(const Block& a, const Block& b, const MergeOptions& o) {
  std::optional<Mesh> out;
  if (detail::count_degenerate_faces(a.mesh) > 0 || detail::count_degenerate_faces(b.mesh) > 0) return std::nullopt;
  detail::warm_up_exact_booleans();
  {
    detail::DeterministicArena arena;
    try {
      ExactMesh ea = detail::to_exact(a.mesh), eb = detail::to_exact(b.mesh), u;
      const auto np = CGAL::parameters::throw_on_self_intersection(true);
      if (PMP::corefine_and_compute_union(ea, eb, u, np, np) && u.number_of_faces() > 0) {
        auto fcc = u.add_property_map<ExactMesh::Face_index, std::size_t>("f:cc", 0).first;
        if (PMP::connected_components(u, fcc) == 1 && exact_height_field(u, a.axis)) {
          detail::SuspendArena heap;
          detail::RoundingReport rounding;
          Mesh m = detail::to_double(u, &rounding);
          if (rounding.num_degenerate_faces == 0 && rounding.num_flipped_faces == 0) out = std::move(m);
        }
      }
    } catch (const std::exception&) {
      // An exact boolean that fails means: do not merge this pair.
    }
  }
  if (!out) return std::nullopt;
  // Check the rounded union like the validator will.
  if (!check_closed_solid(*out).ok() || !is_height_field(*out, axis_direction(a.axis)) ||
      !within_limits(*out, a.axis, o))
    return std::nullopt;
  return out;
}

}  // namespace

MergeResult merge_blocks(std::vector<Block> blocks, const MergeOptions& options) {
  MergeResult result;
  // Every block instance gets an id, so evaluated pairs are not evaluated again.
  std::vector<std::size_t> ids(blocks.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = i;
  std::size_t next_id = blocks.size();
  std::map<std::pair<std::size_t, std::size_t>, bool> rejected;
  for (int round = 0; round < options.max_rounds; ++round) {
    std::vector<BoundingBox> boxes(blocks.size());
    for (std::size_t i = 0; i < blocks.size(); ++i) boxes[i] = bounding_box(blocks[i].mesh);
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    for (std::size_t i = 0; i < blocks.size(); ++i)
      for (std::size_t j = i + 1; j < blocks.size(); ++j)
        if (blocks[i].axis == blocks[j].axis && boxes_touch(boxes[i], boxes[j]) &&
            !rejected.count({ids[i], ids[j]}))
          pairs.emplace_back(i, j);
    if (pairs.empty()) break;
    result.num_candidates += pairs.size();
    std::vector<std::optional<Mesh>> unions(pairs.size());
    parallel_for(0, pairs.size(), [&](std::size_t p) {
      unions[p] = try_union(blocks[pairs[p].first], blocks[pairs[p].second], options);
    });
    std::vector<char> used(blocks.size(), 0);
    std::vector<char> removed(blocks.size(), 0);
    std::size_t merged_now = 0;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      const auto [i, j] = pairs[p];
      if (!unions[p]) {
        rejected[{ids[i], ids[j]}] = true;
        continue;
      }
      if (used[i] || used[j]) continue;  // evaluated again next round
      used[i] = used[j] = 1;
      blocks[i].mesh = std::move(*unions[p]);
      ids[i] = next_id++;
      removed[j] = 1;
      ++merged_now;
    }
    if (merged_now == 0) break;
    result.num_merges += merged_now;
    std::vector<Block> kept;
    std::vector<std::size_t> kept_ids;
    for (std::size_t i = 0; i < blocks.size(); ++i)
      if (!removed[i]) {
        kept.push_back(std::move(blocks[i]));
        kept_ids.push_back(ids[i]);
      }
    blocks = std::move(kept);
    ids = std::move(kept_ids);
  }
  if (options.progress)
    options.progress->info(std::to_string(result.num_merges) + " merges of adjacent same-direction blocks (" +
                           std::to_string(result.num_candidates) + " pairs tried)");
  result.blocks = std::move(blocks);
  return result;
}

}  // namespace subfab
