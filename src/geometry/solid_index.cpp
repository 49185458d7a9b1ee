// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/solid_index.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "geometry/exact_determinant_signs.h"
#include "geometry/exact_normal_signs.h"
#include "geometry/triangle_meets_open_box.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"

namespace subfab::detail {
namespace {

//! Bounding-volume hierarchy over face bounding boxes (median split).
class Bvh {
 public:
  struct Node {
    Box3 bounds;
    double key = 0.0;  // max over the items of their key (build()'s `keys`; 0 without)
    int first = 0;  // leaf: first item; inner: left child (right = left + 1)
    int count = 0;  // > 0: leaf with `count` items
  };

  //! `keys` (optional, indexed by item): each node keeps the max of its items' keys.
  void build(std::vector<int> items, const std::vector<Box3>& boxes, const std::vector<double>* keys = nullptr) {
    items_ = std::move(items);
    nodes_.clear();
    if (items_.empty()) return;
    nodes_.reserve(2 * items_.size() / kLeafSize + 2);
    nodes_.emplace_back();
    build_node(0, 0, static_cast<int>(items_.size()), boxes, keys);
  }

  //! Visits the items of every leaf whose node passes `node_test` (called
  //! with the Node: bounds and key); stops early when `visit(item)` returns
  //! false. Returns false if stopped.
  template <class NodeTest, class Visit>
  bool query(const NodeTest& node_test, const Visit& visit) const {
    if (nodes_.empty()) return true;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[static_cast<std::size_t>(stack[--top])];
      if (!node_test(node)) continue;
      if (node.count > 0) {
        for (int n = 0; n < node.count; ++n)
          if (!visit(items_[static_cast<std::size_t>(node.first + n)])) return false;
      } else {
        stack[top++] = node.first + 1;
        stack[top++] = node.first;
      }
    }
    return true;
  }

 private:
  static constexpr int kLeafSize = 4;

  void build_node(int node_index, int begin, int end, const std::vector<Box3>& boxes,
                  const std::vector<double>* keys) {
    Box3 bounds{Vec3::Constant(std::numeric_limits<double>::infinity()),
                Vec3::Constant(-std::numeric_limits<double>::infinity())};
    Vec3 cmin = bounds.min, cmax = bounds.max;
    double max_key = keys ? -std::numeric_limits<double>::infinity() : 0.0;
    for (int n = begin; n < end; ++n) {
      const auto item = static_cast<std::size_t>(items_[static_cast<std::size_t>(n)]);
      if (keys) max_key = std::max(max_key, (*keys)[item]);
      const Box3& b = boxes[item];
      bounds.min = bounds.min.cwiseMin(b.min);
      bounds.max = bounds.max.cwiseMax(b.max);
      const Vec3 centre = 0.5 * (b.min + b.max);
      cmin = cmin.cwiseMin(centre);
      cmax = cmax.cwiseMax(centre);
    }
    nodes_[static_cast<std::size_t>(node_index)].bounds = bounds;
    nodes_[static_cast<std::size_t>(node_index)].key = max_key;
    if (end - begin <= kLeafSize) {
      nodes_[static_cast<std::size_t>(node_index)].first = begin;
      nodes_[static_cast<std::size_t>(node_index)].count = end - begin;
      return;
    }
    int dim = 0;
    const Vec3 extent = cmax - cmin;
    if (extent[1] > extent[dim]) dim = 1;
    if (extent[2] > extent[dim]) dim = 2;
    const int mid = begin + (end - begin) / 2;
    auto key = [&](int f) {
      const Box3& b = boxes[static_cast<std::size_t>(f)];
      return b.min[dim] + b.max[dim];
    };
    std::nth_element(items_.begin() + begin, items_.begin() + mid, items_.begin() + end, [&](int x, int y) {
      const double kx = key(x), ky = key(y);
      return kx < ky || (kx == ky && x < y);
    });
    const int left = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    nodes_.emplace_back();
    nodes_[static_cast<std::size_t>(node_index)].first = left;
    nodes_[static_cast<std::size_t>(node_index)].count = 0;
    build_node(left, begin, mid, boxes, keys);
    build_node(left + 1, mid, end, boxes, keys);
  }

  std::vector<Node> nodes_;
  std::vector<int> items_;
};

//! Monotone map of doubles to integers (adjacent doubles map to adjacent
//! integers; -0 and +0 both map to 0).
std::int64_t ordered_key(double x) {
  const auto bits = std::bit_cast<std::int64_t>(x);
  return bits >= 0 ? bits : std::numeric_limits<std::int64_t>::min() - bits;
}
double from_ordered_key(std::int64_t key) {
  return key >= 0 ? std::bit_cast<double>(key)
                  : std::bit_cast<double>(std::numeric_limits<std::int64_t>::min() - key);
}

//! Sutherland-Hodgman clip of a convex polygon against x[dim] >= value
//! (sign +1) or x[dim] <= value (sign -1). Approximate (used only to order
//! candidates and to start exact searches).
void clip_polygon(std::vector<Vec3>& poly, int dim, double value, int sign, std::vector<Vec3>& scratch) {
  scratch.clear();
  const std::size_t n = poly.size();
  for (std::size_t m = 0; m < n; ++m) {
    const Vec3& p = poly[m];
    const Vec3& q = poly[(m + 1) % n];
    const double dp = sign * (p[dim] - value);
    const double dq = sign * (q[dim] - value);
    if (dp >= 0) scratch.push_back(p);
    if ((dp >= 0) != (dq >= 0)) {
      const double t = dp / (dp - dq);
      Vec3 x = p + t * (q - p);
      x[dim] = value;
      scratch.push_back(x);
    }
  }
  poly.swap(scratch);
}

}  // namespace

struct SolidIndex::Impl {
  Mesh mesh;
  std::vector<Box3> boxes;                      // per face
  std::vector<std::array<std::int8_t, 3>> normal_signs;  // per face: exact sign of n_x, n_y, n_z
  std::vector<std::array<std::int8_t, 3>> facing;        // per face: facing_signs() (= normal_signs when exact)
  std::array<std::vector<double>, 6> floor;     // per axis, per face: base floor (-inf: faces the axis; +inf: never)
  std::array<std::vector<int>, 6> away;         // per axis: faces with facing_sign < 0 (floor > -inf)
  std::array<Bvh, 6> hard_bvh;                  // per axis, over the faces of `away` with floor +inf
  std::array<Bvh, 6> soft_bvh;                  // per axis, over those with a finite floor (node key: max floor)
  std::array<bool, 6> any_soft{};               // per axis: soft_bvh is not empty
  Bvh all_bvh;                                  // all faces

  const Vec3& vertex(int face, int corner) const {
    return mesh.vertices[static_cast<std::size_t>(mesh.faces[static_cast<std::size_t>(face)][static_cast<std::size_t>(corner)])];
  }
  int facing_sign(int face, Axis axis) const {
    return axis_sign(axis) * facing[static_cast<std::size_t>(face)][static_cast<std::size_t>(axis_dimension(axis))];
  }
  double face_floor(int face, Axis axis) const {
    return floor[static_cast<std::size_t>(axis_index(axis))][static_cast<std::size_t>(face)];
  }
  bool meets(int face, const Box3& box) const {
    return triangle_meets_open_box(vertex(face, 0), vertex(face, 1), vertex(face, 2), box);
  }
  //! Visits the faces facing away from `axis` that block `box` (meet its
  //! open interior and have a base floor above its base); stops when
  //! `visit` returns false (then returns false). `hard` / `soft`: which of
  //! the two lists to search.
  template <class Visit>
  bool visit_blockers(const Box3& box, Axis axis, bool hard, bool soft, const Visit& visit) const;
};

namespace {
//! Does the closed box `node` overlap the open box `box` (could a triangle
//! inside `node` meet the open interior)?
bool overlaps_open(const Box3& node, const Box3& box) {
  return (node.max.array() > box.min.array()).all() && (node.min.array() < box.max.array()).all();
}

//! Sorts distinct face ids below `num_faces` (a query's result, in the BVH's
//! order). A large result is sorted through a bitmap of all faces, linear in
//! num_faces / 64 + its size, instead of a comparison sort (grow's coverage
//! and piece counts query boxes holding most of the mesh).
void sort_face_ids(std::vector<int>& ids, std::size_t num_faces) {
  if (ids.size() < 64 || ids.size() * 16 < num_faces / 64) {
    std::sort(ids.begin(), ids.end());
    return;
  }
  std::vector<std::uint64_t> bits((num_faces + 63) / 64, 0);
  for (int f : ids) bits[static_cast<std::size_t>(f) >> 6] |= std::uint64_t{1} << (static_cast<unsigned>(f) & 63u);
  std::size_t out = 0;
  for (std::size_t w = 0; w < bits.size(); ++w)
    for (std::uint64_t word = bits[w]; word != 0; word &= word - 1)
      ids[out++] = static_cast<int>(64 * w + static_cast<std::size_t>(std::countr_zero(word)));
  ids.resize(out);  // the ids are distinct: out == ids.size()
}
}  // namespace

double box_base(const Box3& box, Axis axis) {
  const int k = axis_dimension(axis);
  return axis_sign(axis) > 0 ? box.min[k] : -box.max[k];
}

template <class Visit>
bool SolidIndex::Impl::visit_blockers(const Box3& box, Axis axis, bool hard, bool soft, const Visit& visit) const {
  const auto ai = static_cast<std::size_t>(axis_index(axis));
  const double base = box_base(box, axis);
  const auto test = [&](int f) {
    return overlaps_open(boxes[static_cast<std::size_t>(f)], box) && floor[ai][static_cast<std::size_t>(f)] > base &&
           meets(f, box);
  };
  if (hard && !hard_bvh[ai].query([&](const auto& node) { return overlaps_open(node.bounds, box); },
                                  [&](int f) { return !test(f) || visit(f); }))
    return false;
  if (soft && any_soft[ai] &&
      !soft_bvh[ai].query([&](const auto& node) { return node.key > base && overlaps_open(node.bounds, box); },
                          [&](int f) { return !test(f) || visit(f); }))
    return false;
  return true;
}

SolidIndex::SolidIndex(const Mesh& mesh, double overhang_sine, const std::vector<std::uint8_t>* allowed,
                       const std::vector<std::array<double, 3>>* floors)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.mesh = mesh;
  const std::size_t nf = mesh.faces.size();
  for (const Triangle& t : mesh.faces)
    for (int v : t)
      if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertices.size())
        throw InvalidMeshError("SolidIndex: face index out of range");
  if (allowed && allowed->size() != nf) throw InvalidArgumentError("SolidIndex: one overhang allowance per face expected");
  if (floors && (!allowed || floors->size() != nf))
    throw InvalidArgumentError("SolidIndex: base floors need the allowances, one entry per face");
  m.boxes.resize(nf);
  m.normal_signs.resize(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const int fi = static_cast<int>(f);
    const Vec3& a = m.vertex(fi, 0);
    const Vec3& b = m.vertex(fi, 1);
    const Vec3& c = m.vertex(fi, 2);
    m.boxes[f].min = a.cwiseMin(b).cwiseMin(c);
    m.boxes[f].max = a.cwiseMax(b).cwiseMax(c);
    for (int k = 0; k < 3; ++k)
      m.normal_signs[f][static_cast<std::size_t>(k)] = static_cast<std::int8_t>(normal_component_sign(a, b, c, k));
  }
  constexpr double inf = std::numeric_limits<double>::infinity();
  // An allowance holds in every box where its floor is -inf (or no floors
  // are given): such faces face the axis (facing_signs()). A finite floor
  // makes it conditional on the box's base; +inf takes it away.
  std::vector<std::uint8_t> everywhere;
  if (allowed) {
    everywhere = *allowed;
    if (floors)
      for (std::size_t f = 0; f < nf; ++f)
        for (std::size_t k = 0; k < 3; ++k)
          if ((*floors)[f][k] != -inf) everywhere[f] = static_cast<std::uint8_t>(everywhere[f] & ~(1u << k));
  }
  m.facing = overhang_sine > 0.0 || allowed ? facing_signs(mesh, overhang_sine, allowed ? &everywhere : nullptr)
                                            : m.normal_signs;
  // The six axes' lists and trees and the tree of all faces are independent:
  // built in parallel (the same trees whatever the thread count).
  parallel_for(0, kAllAxes.size() + 1, [&](std::size_t task) {
    if (task == kAllAxes.size()) {
      std::vector<int> all(nf);
      std::iota(all.begin(), all.end(), 0);
      m.all_bvh.build(std::move(all), m.boxes);
      return;
    }
    const Axis axis = kAllAxes[task];
    const auto ai = static_cast<std::size_t>(axis_index(axis));
    const auto k = static_cast<std::size_t>(axis_dimension(axis));
    auto& fl = m.floor[ai];
    fl.assign(nf, -inf);
    auto& list = m.away[ai];
    std::vector<int> hard, soft;
    for (std::size_t f = 0; f < nf; ++f) {
      if (m.facing_sign(static_cast<int>(f), axis) >= 0) continue;
      list.push_back(static_cast<int>(f));
      const bool conditional = floors && ((*allowed)[f] & (1u << k)) && (*floors)[f][k] < inf;
      fl[f] = conditional ? (*floors)[f][k] : inf;
      (conditional ? soft : hard).push_back(static_cast<int>(f));
    }
    m.any_soft[ai] = !soft.empty();
    m.hard_bvh[ai].build(std::move(hard), m.boxes);
    m.soft_bvh[ai].build(std::move(soft), m.boxes, &fl);
  });
}

SolidIndex::~SolidIndex() = default;
SolidIndex::SolidIndex(SolidIndex&&) noexcept = default;
SolidIndex& SolidIndex::operator=(SolidIndex&&) noexcept = default;

const Mesh& SolidIndex::mesh() const { return impl_->mesh; }
int SolidIndex::num_faces() const { return static_cast<int>(impl_->mesh.faces.size()); }

int SolidIndex::facing_sign(int face, Axis axis) const { return impl_->facing_sign(face, axis); }

const std::vector<int>& SolidIndex::faces_facing_away(Axis axis) const {
  return impl_->away[static_cast<std::size_t>(axis_index(axis))];
}

const Box3& SolidIndex::face_box(int face) const { return impl_->boxes[static_cast<std::size_t>(face)]; }

bool SolidIndex::face_meets_open_box(int face, const Box3& box) const { return impl_->meets(face, box); }

double SolidIndex::base_floor(int face, Axis axis) const { return impl_->face_floor(face, axis); }

bool SolidIndex::has_conditional_faces(Axis axis) const {
  return impl_->any_soft[static_cast<std::size_t>(axis_index(axis))];
}

bool SolidIndex::box_is_valid(const Box3& box, Axis axis) const {
  for (int k = 0; k < 3; ++k)
    if (!(box.max[k] > box.min[k])) return true;
  return impl_->visit_blockers(box, axis, true, true, [](int) { return false; });
}

bool SolidIndex::conditional_faces_allow(const Box3& box, Axis axis) const {
  for (int k = 0; k < 3; ++k)
    if (!(box.max[k] > box.min[k])) return true;
  return impl_->visit_blockers(box, axis, false, true, [](int) { return false; });
}

std::vector<int> SolidIndex::blocking_faces(const Box3& box, Axis axis, std::size_t max_count) const {
  std::vector<int> result;
  for (int k = 0; k < 3; ++k)
    if (!(box.max[k] > box.min[k])) return result;
  impl_->visit_blockers(box, axis, true, true, [&](int f) {
    result.push_back(f);
    return true;
  });
  sort_face_ids(result, impl_->mesh.faces.size());
  if (result.size() > max_count) result.resize(max_count);
  return result;
}

std::vector<int> SolidIndex::faces_meeting_open_box(const Box3& box) const {
  std::vector<int> result;
  for (int k = 0; k < 3; ++k)
    if (!(box.max[k] > box.min[k])) return result;
  const Impl& m = *impl_;
  m.all_bvh.query([&](const auto& node) { return overlaps_open(node.bounds, box); },
                  [&](int f) {
                    if (overlaps_open(m.boxes[static_cast<std::size_t>(f)], box) && m.meets(f, box))
                      result.push_back(f);
                    return true;
                  });
  sort_face_ids(result, m.mesh.faces.size());
  return result;
}

bool SolidIndex::any_face_meets_open_box(const Box3& box) const {
  for (int k = 0; k < 3; ++k)
    if (!(box.max[k] > box.min[k])) return false;
  const Impl& m = *impl_;
  return !m.all_bvh.query([&](const auto& node) { return overlaps_open(node.bounds, box); },
                          [&](int f) { return !(overlaps_open(m.boxes[static_cast<std::size_t>(f)], box) && m.meets(f, box)); });
}

std::vector<int> SolidIndex::faces_near_closed_box(const Box3& box) const {
  std::vector<int> result;
  const Impl& m = *impl_;
  auto touches = [&](const Box3& b) {
    return (b.max.array() >= box.min.array()).all() && (b.min.array() <= box.max.array()).all();
  };
  m.all_bvh.query([&](const auto& node) { return touches(node.bounds); }, [&](int f) {
    if (touches(m.boxes[static_cast<std::size_t>(f)])) result.push_back(f);
    return true;
  });
  sort_face_ids(result, m.mesh.faces.size());
  return result;
}

bool SolidIndex::face_covered(int face, const Box3& box, Axis axis) const {
  const Impl& m = *impl_;
  const Box3& fb = m.boxes[static_cast<std::size_t>(face)];
  if (!box.contains(fb.min) || !box.contains(fb.max)) return false;
  bool in_some_plane = false;
  const auto& s = m.normal_signs[static_cast<std::size_t>(face)];
  for (int k = 0; k < 3; ++k) {
    // The face lies in plane x_k = box.min[k] iff all its vertices do, i.e.
    // its bounding box has max == box.min there.
    if (fb.max[k] == box.min[k]) {
      in_some_plane = true;
      if (s[static_cast<std::size_t>(k)] >= 0 && (s[0] != 0 || s[1] != 0 || s[2] != 0)) return false;
    }
    if (fb.min[k] == box.max[k]) {
      in_some_plane = true;
      if (s[static_cast<std::size_t>(k)] <= 0 && (s[0] != 0 || s[1] != 0 || s[2] != 0)) return false;
    }
  }
  if (in_some_plane) return true;
  return m.face_floor(face, axis) <= box_base(box, axis);  // facing d, or allowed at this box's base
}

std::vector<int> SolidIndex::faces_covered(const Box3& box, Axis axis) const {
  std::vector<int> result;
  const Impl& m = *impl_;
  m.all_bvh.query(
      [&](const auto& node) {
        return (node.bounds.max.array() >= box.min.array()).all() && (node.bounds.min.array() <= box.max.array()).all();
      },
      [&](int f) {
        if (face_covered(f, box, axis)) result.push_back(f);
        return true;
      });
  sort_face_ids(result, m.mesh.faces.size());
  return result;
}

double SolidIndex::push_face(const Box3& box, Axis axis, int dim, int side, double limit) const {
  const Impl& m = *impl_;
  const double current = side > 0 ? box.max[dim] : box.min[dim];
  if (side > 0 ? !(limit > current) : !(limit < current)) return current;
  for (int k = 0; k < 3; ++k)
    if (k != dim && !(box.max[k] > box.min[k])) return limit;  // interior stays empty
  Box3 region = box;
  (side > 0 ? region.max[dim] : region.min[dim]) = limit;
  auto box_at = [&](double t) {
    Box3 b = box;
    (side > 0 ? b.max[dim] : b.min[dim]) = t;
    return b;
  };

  // Candidates: facing-away faces whose bounding box reaches the moving
  // face's plane and overlaps the swept region's open interior laterally
  // (and, for a face allowed above a base floor, whose floor lies above the
  // base somewhere on the way). A face blocks the box at t when it meets its
  // open interior and its floor lies above the box's base: both grow
  // monotonically with the motion, so the first blocking position is found
  // by bisection as for a plain contact.
  const auto ai = static_cast<std::size_t>(axis_index(axis));
  const bool moves_base = dim == axis_dimension(axis) && side == -axis_sign(axis);
  const double base_now = box_base(box, axis);
  const double base_lowest = box_base(region, axis);
  // Candidates are ordered by where their bounding box begins along the
  // motion (no face blocks before it), and a face's approximate contact is
  // computed only when that lies before the best position so far: the
  // contact found is the same in any order (each face's first blocking
  // position is found exactly), and most faces of a long sweep lie beyond it.
  struct Candidate {
    double reach;  // where the face's bounding box begins along the motion (>= current)
    int face;
  };
  std::vector<Candidate> candidates;
  const auto collect = [&](int f) {
    const Box3& fb = m.boxes[static_cast<std::size_t>(f)];
    if (!overlaps_open(fb, region)) return true;
    const double fl = m.floor[ai][static_cast<std::size_t>(f)];
    if (!(fl > base_lowest)) return true;  // allowed all the way
    const bool soft = moves_base && !(fl > base_now);  // blocks only once the base passes its floor
    if (!soft && (side > 0 ? fb.max[dim] < current : fb.min[dim] > current)) return true;
    candidates.push_back({side > 0 ? std::max(current, fb.min[dim]) : std::min(current, fb.max[dim]), f});
    return true;
  };
  m.hard_bvh[ai].query([&](const auto& node) { return overlaps_open(node.bounds, region); }, collect);
  if (m.any_soft[ai])
    m.soft_bvh[ai].query([&](const auto& node) { return node.key > base_lowest && overlaps_open(node.bounds, region); },
                         collect);
  std::sort(candidates.begin(), candidates.end(), [&](const Candidate& x, const Candidate& y) {
    if (x.reach != y.reach) return side > 0 ? x.reach < y.reach : x.reach > y.reach;
    return x.face < y.face;
  });
  // Approximate first blocking position of face f: clip the triangle to the
  // closed swept region.
  std::vector<Vec3> poly, scratch;
  const auto estimate_of = [&](int f) {
    const Box3& fb = m.boxes[static_cast<std::size_t>(f)];
    const double fl = m.floor[ai][static_cast<std::size_t>(f)];
    const bool soft = moves_base && !(fl > base_now);
    poly = {m.vertex(f, 0), m.vertex(f, 1), m.vertex(f, 2)};
    for (int k = 0; k < 3 && !poly.empty(); ++k) {
      if (k == dim) continue;
      clip_polygon(poly, k, box.min[k], +1, scratch);
      if (!poly.empty()) clip_polygon(poly, k, box.max[k], -1, scratch);
    }
    if (!poly.empty()) clip_polygon(poly, dim, current, side, scratch);
    double estimate = limit;
    for (const Vec3& p : poly) estimate = side > 0 ? std::min(estimate, p[dim]) : std::max(estimate, p[dim]);
    if (soft) {
      if (fb.max[dim] > box.min[dim] && fb.min[dim] < box.max[dim]) estimate = current;  // may meet the box already
      const double crossing = -side * fl;  // where the base passes the floor
      estimate = side > 0 ? std::max(estimate, crossing) : std::min(estimate, crossing);
      estimate = side > 0 ? std::min(estimate, limit) : std::max(estimate, limit);
    }
    if (side > 0 ? !(estimate >= current) : !(estimate <= current)) estimate = current;
    return estimate;
  };

  // Keys increase in the direction of motion.
  auto key = [&](double t) { return side * ordered_key(t); };
  auto value = [&](std::int64_t k) { return from_ordered_key(side * k); };
  double best = limit;
  for (const Candidate& cand : candidates) {
    // The face can only meet the open box at `best` if it reaches below it;
    // the faces after it begin no earlier.
    if (side > 0 ? !(cand.reach < best) : !(cand.reach > best)) break;
    const double fl = m.floor[ai][static_cast<std::size_t>(cand.face)];
    const auto blocks = [&](double t) {
      const Box3 b = box_at(t);
      return fl > box_base(b, axis) && m.meets(cand.face, b);
    };
    if (!blocks(best)) continue;
    // Largest t in [current, best) with no contact: lo never meets (the box
    // at `current` is valid), hi meets; gallop from the estimate, then bisect.
    std::int64_t lo = key(current);
    std::int64_t hi = key(best);
    auto meets_key = [&](std::int64_t k) { return blocks(value(k)); };
    std::int64_t guess = std::clamp(key(estimate_of(cand.face)), lo, hi);
    if (guess > lo && guess < hi) {
      if (meets_key(guess)) {
        hi = guess;
        for (std::int64_t step = 1; hi - lo > 1; step *= 2) {
          const std::int64_t probe = hi - step;
          if (probe <= lo) break;
          if (meets_key(probe)) {
            hi = probe;
          } else {
            lo = probe;
            break;
          }
        }
      } else {
        lo = guess;
        for (std::int64_t step = 1; hi - lo > 1; step *= 2) {
          const std::int64_t probe = lo + step;
          if (probe >= hi) break;
          if (meets_key(probe)) {
            hi = probe;
            break;
          }
          lo = probe;
        }
      }
    }
    while (hi - lo > 1) {
      const std::int64_t mid = lo + (hi - lo) / 2;
      if (meets_key(mid))
        hi = mid;
      else
        lo = mid;
    }
    best = value(lo);
  }
  return best;
}

bool SolidIndex::is_inside(const Vec3& p) const {
  const Impl& m = *impl_;
  // Ray from q = p + (e, e^2, e^3) towards +z.
  int crossings = 0;
  // Sign of orient2d(u, w, q) in the xy plane with q_xy = p_xy + (e, e^2).
  auto edge_sign = [&](const Vec3& u, const Vec3& w) {
    const int s = det2_sign(w.x(), u.x(), w.y(), u.y(), p.x(), u.x(), p.y(), u.y());
    if (s != 0) return s;
    // + (w_x - u_x) e^2 - (w_y - u_y) e
    const int sy = sign_of_number(u.y() - w.y());
    if (sy != 0) return sy;
    return sign_of_number(w.x() - u.x());
  };
  m.all_bvh.query(
      [&](const auto& n) {
        const Box3& node = n.bounds;
        return node.min.x() <= p.x() && p.x() <= node.max.x() && node.min.y() <= p.y() && p.y() <= node.max.y() &&
               node.max.z() >= p.z();
      },
      [&](int f) {
        const Box3& fb = m.boxes[static_cast<std::size_t>(f)];
        if (!(fb.min.x() <= p.x() && p.x() <= fb.max.x() && fb.min.y() <= p.y() && p.y() <= fb.max.y() &&
              fb.max.z() >= p.z()))
          return true;
        const auto& s = m.normal_signs[static_cast<std::size_t>(f)];
        const int sz = s[2];
        if (sz == 0) return true;  // vertical: the perturbed ray misses it
        const Vec3& a = m.vertex(f, 0);
        const Vec3& b = m.vertex(f, 1);
        const Vec3& c = m.vertex(f, 2);
        if (edge_sign(a, b) != sz || edge_sign(b, c) != sz || edge_sign(c, a) != sz) return true;
        int o = orient3d_sign(a, b, c, p);
        if (o == 0) o = s[0] != 0 ? s[0] : (s[1] != 0 ? s[1] : s[2]);
        if (o * sz < 0) ++crossings;  // q is below the plane: the ray crosses it
        return true;
      });
  return (crossings % 2) == 1;
}

}  // namespace subfab::detail
