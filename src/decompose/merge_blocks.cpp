// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/merge_blocks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "decompose/block_pairs_detail.h"
#include "geometry/exact_mesh.h"
#include "geometry/triangle_tree.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/finalize_blocks.h"
#include "subfab/validate/validate_decomposition.h"

namespace subfab {
namespace {

using detail::ExactMesh;
using detail::ExactPoint;

//! Exact height-field test of a closed exact mesh along an axis; under an
//! overhang allowance s > 0 a face with unit n.d >= -s also passes.
bool exact_height_field(const ExactMesh& m, Axis axis, double sine) {
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
    if (sine > 0.0 && CGAL::to_double(nd) >= -sine * std::sqrt(CGAL::to_double(n.squared_length())))
      continue;
    for (const ExactPoint* p : {&a, &b, &c})
      if ((s > 0 ? (*p)[k] : -(*p)[k]) != *base) return false;
  }
  return true;
}

//! Cheap necessary condition for the union of `self` and `other` to be a
//! height field along `axis`: every face of `self` that clearly faces away
//! from the axis lies on the union's base level or is glued to `other` (and
//! vanishes from the union): inside `other`'s bounding box, and its centroid
//! on `other`'s surface (`other_tree`, built on first use; a face partly
//! glued keeps its other part on the union's surface). Faces too small to
//! decide (an edge, or the height under the longest edge, within `small`:
//! cleaned_union() may clean such specks away) are only held to the box.
//! Only rejects, the exact test decides.
bool may_be_height_field(const Mesh& self, const Mesh& other, const BoundingBox& other_box, Axis axis, double base,
                         double tol, double small, std::unique_ptr<detail::TriangleTree>& other_tree) {
  const Vec3 d = axis_direction(axis);
  for (const Triangle& t : self.faces) {
    const Vec3& a = self.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = self.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = self.vertices[static_cast<std::size_t>(t[2])];
    const Vec3 n = (b - a).cross(c - a);
    if (!(n.dot(d) < -1e-6 * n.norm())) continue;
    if (std::max({a.dot(d), b.dot(d), c.dot(d)}) <= base + tol) continue;
    bool inside = true;
    for (const Vec3* p : {&a, &b, &c})
      inside = inside && (p->array() >= other_box.min.array() - tol).all() &&
               (p->array() <= other_box.max.array() + tol).all();
    if (!inside) return false;
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const double shortest = std::min({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    if (shortest <= small || n.norm() <= small * longest) continue;  // a speck (height <= small)
    if (!other_tree) other_tree = std::make_unique<detail::TriangleTree>(other);
    const Vec3 centroid = (a + b + c) / 3.0;
    if (!(other_tree->tree().squared_distance(detail::TriangleTree::point(centroid)) <= small * small)) return false;
  }
  return true;
}

//! The milling directions worth an exact test for the union of a and b, in
//! order: the larger block's, the other's, then (with `any_direction`) the
//! remaining ones; only those that pass may_be_height_field for both blocks.
std::vector<Axis> union_axes(const Block& a, const Block& b, const BoundingBox& ba, const BoundingBox& bb,
                             double volume_a, double volume_b, bool any_direction) {
  std::vector<Axis> axes{a.axis};
  if (b.axis != a.axis) axes.insert(volume_b > volume_a ? axes.begin() : axes.end(), b.axis);
  if (any_direction)
    for (Axis x : kAllAxes)
      if (std::find(axes.begin(), axes.end(), x) == axes.end()) axes.push_back(x);
  const double tol = 1e-12 * std::max({1.0, ba.diagonal(), bb.diagonal()});
  // Far above export's cleanup tolerance (1e-10 x scale) and any rounding
  // of a glued face's centroid.
  const double small = 1e-8 * std::max({1.0, ba.diagonal(), bb.diagonal()});
  std::unique_ptr<detail::TriangleTree> tree_a, tree_b;
  std::vector<Axis> out;
  for (Axis axis : axes) {
    const Vec3 d = axis_direction(axis);
    double base = std::numeric_limits<double>::infinity();
    for (const Mesh* m : {&a.mesh, &b.mesh})
      for (const Vec3& v : m->vertices) base = std::min(base, v.dot(d));
    if (may_be_height_field(a.mesh, b.mesh, bb, axis, base, tol, small, tree_b) &&
        may_be_height_field(b.mesh, a.mesh, ba, axis, base, tol, small, tree_a))
      out.push_back(axis);
  }
  return out;
}

//! A valid merged block: the union and its milling direction.
struct Union {
  Mesh mesh;
  Axis axis = Axis::PosZ;
};

//! Can export's cleanup (clean_rounded_block(): edges shorter than `tol`
//! collapsed, caps lower than it flipped) remove every face of `mesh` that
//! keeps it from being a height field along d: each face facing away from
//! d (n.d < 0) off the base level has an edge shorter than `tol` or a
//! height under its longest edge below it? A cheap necessary condition.
bool only_specks_face_away(const Mesh& mesh, const Vec3& d, double tol) {
  double base = std::numeric_limits<double>::infinity();
  for (const Vec3& v : mesh.vertices) base = std::min(base, v.dot(d));
  for (const Triangle& t : mesh.faces) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    const Vec3 n = (b - a).cross(c - a);
    if (!(n.dot(d) < 0) || std::max({a.dot(d), b.dot(d), c.dot(d)}) <= base) continue;
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const double shortest = std::min({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    if (!(shortest < tol || n.norm() < tol * longest)) return false;
  }
  return true;
}

//! Does the rounded union `m` pass export's block check along `axis`
//! (block_defect(): closed, no zero-area face, height field with the
//! overhang allowance, no self-intersection) and fit the limits?
bool valid_union(const Mesh& m, Axis axis, const MergeOptions& o) {
  FinalizeOptions check;
  check.normal_tolerance = height_field_normal_tolerance(o.max_overhang_deg);
  const BoundingBox box = bounding_box(m);
  return block_defect(m, axis_direction(axis), box.diagonal(), check).empty() &&
         detail::within_limits(box, axis, o.max_height, o.machine_size);
}

//! The rounded union of two blocks whose exact union is no height field
//! along any of `axes` only because of specks: faces far below export's
//! cleanup tolerance that the corefinement leaves where the glued faces
//! meet (bunny_lowres at 1e-3: one face of area 4e-22 facing up inside a
//! -z union). The union gets the cleanup every block gets at export, along
//! each axis in turn, and is kept for the first along which it is then a
//! closed solid, a height field with no off-base face facing away at all
//! (unit n.d >= 0, or the overhang allowance), passing export's block check,
//! within the limits.
std::optional<Union> cleaned_union(const Mesh& rounded, const std::vector<Axis>& axes, const MergeOptions& o) {
  const FinalizeOptions fo;
  const double tol = fo.relative_tolerance * rounding_scale(rounded);
  HeightFieldOptions strict;
  strict.normal_tolerance = o.max_overhang_deg > 0 ? height_field_normal_tolerance(o.max_overhang_deg) : 0.0;
  for (Axis axis : axes) {
    const Vec3 d = axis_direction(axis);
    if (!only_specks_face_away(rounded, d, tol)) continue;
    Mesh m = rounded;
    try {
      clean_rounded_block(m, d, tol, fo);
    } catch (const std::exception&) {
      continue;
    }
    if (m.faces.empty()) continue;
    if (!check_closed_solid(m).ok() || !is_height_field(m, d, strict) || !valid_union(m, axis, o)) continue;
    return Union{std::move(m), axis};
  }
  return std::nullopt;
}

//! The union of two blocks if it is a valid block along one of `axes` (the
//! first that is), computed in a private arena. When rounding the exact
//! union to doubles makes faces degenerate or flipped (thin triangles where
//! the corefinement cut the glued faces), the rounded union gets the
//! cleanup every block gets at export (clean_rounded_block, same relative
//! tolerance) and is kept only if it then passes export's block check. When
//! the exact union is a height field along none of them, cleaned_union()
//! decides (specks of the corefinement).
std::optional<Union> try_union(const Block& a, const Block& b, const std::vector<Axis>& axes, const MergeOptions& o) {
  if (axes.empty()) return std::nullopt;
  const double sine = overhang_sine(o.max_overhang_deg);
  Axis union_axis = Axis::PosZ;
  bool exact_axis = false;
  detail::RoundingReport rounding;
  std::optional<Mesh> mesh = detail::exact_block_union(
      a.mesh, b.mesh,
      [&](const ExactMesh& u) {
        const auto axis = std::find_if(axes.begin(), axes.end(), [&](Axis x) { return exact_height_field(u, x, sine); });
        if (axis != axes.end()) {
          union_axis = *axis;
          exact_axis = true;
        }
        return true;  // rounded either way: cleaned_union() may still take it
      },
      rounding);
  if (!mesh) return std::nullopt;
  if (!exact_axis) return cleaned_union(*mesh, axes, o);
  std::optional<Union> out = Union{std::move(*mesh), union_axis};
  const bool needs_cleanup = rounding.num_degenerate_faces + rounding.num_flipped_faces > 0;
  if (needs_cleanup) {
    FinalizeOptions fo;
    fo.normal_tolerance = height_field_normal_tolerance(o.max_overhang_deg);
    try {
      clean_rounded_block(out->mesh, axis_direction(out->axis), fo.relative_tolerance * rounding_scale(out->mesh), fo);
    } catch (const std::exception&) {
      return std::nullopt;
    }
  }
  // Check the rounded union as the export will (closed, no zero-area face,
  // height field, no self-intersection): humanoid.off at 1e-3 merged a
  // milled block with a neighbour into a union whose faces crossed (66
  // pairs), which the export then refused (exit 3).
  if (!valid_union(out->mesh, out->axis, o)) return std::nullopt;
  return out;
}

}  // namespace

MergeResult merge_blocks(std::vector<Block> blocks, const MergeOptions& options) {
  MergeResult result;
  // Every block instance gets an id, so evaluated pairs are not evaluated again.
  std::vector<std::size_t> ids(blocks.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = i;
  std::size_t next_id = blocks.size();
  std::vector<std::vector<std::size_t>> parts(blocks.size());
  for (std::size_t i = 0; i < parts.size(); ++i) parts[i] = {i};
  std::map<std::pair<std::size_t, std::size_t>, bool> rejected;
  for (int round = 0; round < options.max_rounds; ++round) {
    const std::vector<BoundingBox> boxes = detail::block_boxes(blocks);
    const std::vector<double> volumes = detail::block_volumes(blocks);
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    for (std::size_t i = 0; i < blocks.size(); ++i)
      for (std::size_t j = i + 1; j < blocks.size(); ++j)
        if ((options.any_direction || blocks[i].axis == blocks[j].axis) && detail::boxes_touch(boxes[i], boxes[j]) &&
            !rejected.count({ids[i], ids[j]}))
          pairs.emplace_back(i, j);
    if (pairs.empty()) break;
    std::vector<std::optional<Union>> unions(pairs.size());
    std::vector<char> tried(pairs.size(), 0);
    parallel_for(0, pairs.size(), [&](std::size_t p) {
      const auto [i, j] = pairs[p];
      const std::vector<Axis> axes =
          union_axes(blocks[i], blocks[j], boxes[i], boxes[j], volumes[i], volumes[j], options.any_direction);
      tried[p] = axes.empty() ? 0 : 1;
      unions[p] = try_union(blocks[i], blocks[j], axes, options);
    });
    for (char t : tried) result.num_candidates += static_cast<std::size_t>(t);
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
      blocks[i].mesh = std::move(unions[p]->mesh);
      blocks[i].axis = unions[p]->axis;
      ids[i] = next_id++;
      parts[i].insert(parts[i].end(), parts[j].begin(), parts[j].end());
      std::sort(parts[i].begin(), parts[i].end());
      removed[j] = 1;
      ++merged_now;
    }
    if (merged_now == 0) break;
    result.num_merges += merged_now;
    std::vector<Block> kept;
    std::vector<std::size_t> kept_ids;
    std::vector<std::vector<std::size_t>> kept_parts;
    for (std::size_t i = 0; i < blocks.size(); ++i)
      if (!removed[i]) {
        kept.push_back(std::move(blocks[i]));
        kept_ids.push_back(ids[i]);
        kept_parts.push_back(std::move(parts[i]));
      }
    blocks = std::move(kept);
    ids = std::move(kept_ids);
    parts = std::move(kept_parts);
  }
  if (options.progress)
    options.progress->info(std::to_string(result.num_merges) + " merges of adjacent blocks (" +
                           std::to_string(result.num_candidates) + " pairs tried exactly)");
  result.blocks = std::move(blocks);
  result.parts = std::move(parts);
  return result;
}

}  // namespace subfab
