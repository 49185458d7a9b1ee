// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/grow_boxes.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <unordered_map>

#include "decompose/box_pieces.h"
#include "geometry/solid_index.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/mesh/refine_mesh.h"

namespace subfab {
namespace {

using detail::SolidIndex;

constexpr double kInf = std::numeric_limits<double>::infinity();

// --- Grid planes -------------------------------------------------------------

//! Smallest plane index with coordinate > x (num_points if none).
int plane_above(const GridGeometry& g, int dim, double x) {
  const int n = g.num_points[static_cast<std::size_t>(dim)];
  int i = static_cast<int>(std::floor((x - g.origin[dim]) / g.spacing));
  i = std::clamp(i, -1, n);
  while (i < n && (i < 0 || g.coordinate(dim, i) <= x)) ++i;
  while (i > 0 && g.coordinate(dim, i - 1) > x) --i;
  return i;
}
//! Largest plane index with coordinate < x (-1 if none).
int plane_below(const GridGeometry& g, int dim, double x) {
  const int n = g.num_points[static_cast<std::size_t>(dim)];
  int i = static_cast<int>(std::ceil((x - g.origin[dim]) / g.spacing));
  i = std::clamp(i, -1, n);
  while (i >= 0 && (i >= n || g.coordinate(dim, i) >= x)) --i;
  while (i + 1 < n && g.coordinate(dim, i + 1) < x) ++i;
  return i;
}
//! Largest plane index with coordinate <= x, clamped to the grid.
int plane_at_or_below(const GridGeometry& g, int dim, double x) {
  const int n = g.num_points[static_cast<std::size_t>(dim)];
  return std::clamp(plane_above(g, dim, x) - 1, 0, n - 1);
}
//! Smallest plane index with coordinate >= x, clamped to the grid.
int plane_at_or_above(const GridGeometry& g, int dim, double x) {
  const int n = g.num_points[static_cast<std::size_t>(dim)];
  return std::clamp(plane_below(g, dim, x) + 1, 0, n - 1);
}

// --- Size limits -------------------------------------------------------------

struct SizeLimits {
  double max_height = kInf;   // along the axis
  Vec3 machine = Vec3::Constant(kInf);

  //! Largest extent allowed along `dim` for a box milled along `axis`,
  //! given the box's current extents in the other dimensions.
  double extent_limit(const Box3& b, Axis axis, int dim) const {
    const int ad = axis_dimension(axis);
    if (dim == ad) return std::min(max_height, machine.z());
    const int other = 3 - ad - dim;
    const double e = b.max[other] - b.min[other];
    double limit = -kInf;
    if (e <= machine.y()) limit = std::max(limit, machine.x());
    if (e <= machine.x()) limit = std::max(limit, machine.y());
    return limit;
  }
  bool fits(const Box3& b, Axis axis) const { return box_fits_limits(b, axis, max_height, machine); }
  //! `target` clamped so that the box's extent along dim stays within the limit.
  double clamp(const Box3& b, Axis axis, int dim, int side, double target) const {
    const double limit = extent_limit(b, axis, dim);
    if (limit == kInf) return target;
    if (side > 0) {
      if (!(limit >= 0)) return b.max[dim];
      double t = b.min[dim] + limit;
      while (t - b.min[dim] > limit) t = std::nextafter(t, -kInf);
      return std::max(b.max[dim], std::min(target, t));
    }
    if (!(limit >= 0)) return b.min[dim];
    double t = b.max[dim] - limit;
    while (b.max[dim] - t > limit) t = std::nextafter(t, kInf);
    return std::min(b.min[dim], std::max(target, t));
  }
};

// --- Growth of one box -------------------------------------------------------

class Grower {
 public:
  //! \param fields_describe_mesh false when `index` holds a refinement of the
  //!        mesh the fields were computed on: refine_mesh()'s rounded
  //!        midpoints can tilt a sub-triangle of a face parallel to an axis by
  //!        a hair, so that it faces away from that axis where its parent did
  //!        not; the fields do not know it, and every move is then decided by
  //!        the exact index alone.
  Grower(const SolidIndex& index, const std::array<HeightField, 6>& fields, const SizeLimits& limits,
         bool maximal, bool fields_describe_mesh)
      : index_(index),
        fields_(fields),
        grid_(fields[0].grid),
        limits_(limits),
        maximal_(maximal),
        fields_describe_mesh_(fields_describe_mesh) {
    for (int d = 0; d < 3; ++d) {
      domain_.min[d] = grid_.coordinate(d, 0);
      domain_.max[d] = grid_.coordinate(d, grid_.num_points[static_cast<std::size_t>(d)] - 1);
    }
  }

  //! The grown box for seed `face` and `axis`, or nullopt if no valid box
  //! for that axis covers the face. `strategy` picks which maximal box.
  std::optional<Box3> grow(int face, Axis axis, GrowStrategy strategy) const {
    if (index_.facing_sign(face, axis) < 0) return std::nullopt;
    Box3 b = index_.face_box(face);
    if (!limits_.fits(b, axis)) return std::nullopt;
    if (!index_.box_is_valid(b, axis)) return std::nullopt;
    const Mesh& mesh = index_.mesh();
    // 1. Give the box thickness where the seed is flat: push the side where
    //    the solid is (opposite to the normal) first.
    const Vec3 n = face_normal_scaled(mesh, static_cast<std::size_t>(face));
    for (int dim = 0; dim < 3; ++dim) {
      if (b.min[dim] != b.max[dim]) continue;
      const int side = n[dim] > 0 ? -1 : +1;
      move(b, axis, dim, side, next_plane(dim, side, b));
      if (b.min[dim] == b.max[dim]) return std::nullopt;  // blocked at once: thin feature
    }
    // 2. Snap every side outward to its grid plane where possible.
    std::array<bool, 6> frozen{};
    for (int s = 0; s < 6; ++s) {
      const int dim = s / 2, side = (s % 2) ? +1 : -1;
      const double cur = side > 0 ? b.max[dim] : b.min[dim];
      const double target = side > 0 ? grid_.coordinate(dim, plane_at_or_above(grid_, dim, cur))
                                     : grid_.coordinate(dim, plane_at_or_below(grid_, dim, cur));
      if (target == cur) continue;
      if (!move(b, axis, dim, side, target)) frozen[static_cast<std::size_t>(s)] = true;
    }
    if (strategy != GrowStrategy::Greedy) {
      grow_round_robin(b, axis, frozen, strategy == GrowStrategy::AcrossFirst);
    } else {
      grow_greedy(b, axis, frozen);
    }
    // 4. Make the box maximal: push every side to first contact (or the
    //    size limit / grid domain), the sides across the axis first; then
    //    no side can move without breaking validity or a limit.
    if (maximal_) {
      const int ad = axis_dimension(axis);
      for (int k = 1; k <= 3; ++k) {
        const int dim = (ad + k) % 3;
        for (int side : {+1, -1}) move(b, axis, dim, side, side > 0 ? domain_.max[dim] : domain_.min[dim]);
      }
    }
    if (!index_.face_covered(face, b, axis)) return std::nullopt;
    shrink_to_coverage(b, axis);
    return b;
  }

 private:
  //! Round-robin growth: every unfrozen side in turn moves out by one grid
  //! plane (exactly limited by first contact), until all are blocked; with
  //! `across_first`, the four sides across the axis grow to contact first,
  //! then the two along it. Balanced boxes: wide where the shape allows.
  void grow_round_robin(Box3& b, Axis axis, std::array<bool, 6> frozen, bool across_first) const {
    const int ad = axis_dimension(axis);
    for (int phase = across_first ? 0 : 1; phase < 2; ++phase) {
      for (bool moved = true; moved;) {
        moved = false;
        for (int s = 0; s < 6; ++s) {
          const int dim = s / 2, side = (s % 2) ? +1 : -1;
          if (frozen[static_cast<std::size_t>(s)] || (phase == 0 && dim == ad)) continue;
          const double cur = side > 0 ? b.max[dim] : b.min[dim];
          const double target = limits_.clamp(b, axis, dim, side, next_plane(dim, side, b));
          if (target == cur) {
            frozen[static_cast<std::size_t>(s)] = true;
            continue;
          }
          if (!move(b, axis, dim, side, target)) frozen[static_cast<std::size_t>(s)] = true;
          moved = moved || (side > 0 ? b.max[dim] : b.min[dim]) != cur;
        }
      }
    }
  }

  //! Greedy growth: move the side whose next plane holds the most Good
  //! points (Appendix B's objective, minimised one plane at a time).
  void grow_greedy(Box3& b, Axis axis, std::array<bool, 6> frozen) const {
    const HeightField& field = fields_[static_cast<std::size_t>(axis_index(axis))];
    for (;;) {
      int best = -1;
      std::int64_t best_gain = 0;
      double best_target = 0;
      std::array<int, 3> lo{}, hi{};
      for (int d = 0; d < 3; ++d) {
        lo[static_cast<std::size_t>(d)] = plane_at_or_below(grid_, d, b.min[d]);
        hi[static_cast<std::size_t>(d)] = plane_at_or_above(grid_, d, b.max[d]);
      }
      for (int s = 0; s < 6; ++s) {
        if (frozen[static_cast<std::size_t>(s)]) continue;
        const int dim = s / 2, side = (s % 2) ? +1 : -1;
        const int p = side > 0 ? plane_above(grid_, dim, b.max[dim]) : plane_below(grid_, dim, b.min[dim]);
        if (p < 0 || p >= grid_.num_points[static_cast<std::size_t>(dim)]) {
          frozen[static_cast<std::size_t>(s)] = true;
          continue;
        }
        const double target = limits_.clamp(b, axis, dim, side, grid_.coordinate(dim, p));
        if (target == (side > 0 ? b.max[dim] : b.min[dim])) {
          frozen[static_cast<std::size_t>(s)] = true;
          continue;
        }
        std::array<int, 3> slo = lo, shi = hi;
        slo[static_cast<std::size_t>(dim)] = shi[static_cast<std::size_t>(dim)] = p;
        const std::int64_t gain = field.count_good(slo, shi);
        if (gain > best_gain) {
          best_gain = gain;
          best = s;
          best_target = target;
        }
      }
      if (best < 0) break;
      const int dim = best / 2, side = (best % 2) ? +1 : -1;
      if (!move(b, axis, dim, side, best_target)) frozen[static_cast<std::size_t>(best)] = true;
    }
  }

  //! Next grid plane beyond the side (or the domain bound), size-clamped.
  double next_plane(int dim, int side, const Box3& b) const {
    if (side > 0) {
      const int p = plane_above(grid_, dim, b.max[dim]);
      return p < grid_.num_points[static_cast<std::size_t>(dim)] ? grid_.coordinate(dim, p)
                                                                 : std::max(b.max[dim], domain_.max[dim]);
    }
    const int p = plane_below(grid_, dim, b.min[dim]);
    return p >= 0 ? grid_.coordinate(dim, p) : std::min(b.min[dim], domain_.min[dim]);
  }

  //! Moves a side towards `target` (size-clamped) as far as exactly valid.
  //! Returns true if it reached the target.
  bool move(Box3& b, Axis axis, int dim, int side, double target) const {
    const double clamped = limits_.clamp(b, axis, dim, side, target);
    Box3 moved = b;
    (side > 0 ? moved.max[dim] : moved.min[dim]) = clamped;
    // Same answer as push_face without its exact queries: no face blocks by
    // the grid, and no face allowed only above a base floor (the field counts
    // those as facing) blocks exactly.
    if (fields_describe_mesh_ && grid_says_valid(moved, axis) &&
        (!index_.has_conditional_faces(axis) || index_.conditional_faces_allow(moved, axis))) {
      (side > 0 ? b.max[dim] : b.min[dim]) = clamped;
      return clamped == target;
    }
    const double t = index_.push_face(b, axis, dim, side, clamped);
    (side > 0 ? b.max[dim] : b.min[dim]) = t;
    return t == target;
  }

  //! Sufficient test: the grid points around `b` hold no Forbidden point of
  //! the axis's field, so no facing-away triangle meets the closed box (see
  //! compute_field.h). False when unsure (then ask the exact index).
  bool grid_says_valid(const Box3& b, Axis axis) const {
    std::array<int, 3> lo{}, hi{};
    for (int d = 0; d < 3; ++d) {
      const auto du = static_cast<std::size_t>(d);
      lo[du] = plane_at_or_below(grid_, d, b.min[d]);
      hi[du] = plane_at_or_above(grid_, d, b.max[d]);
      if (!(grid_.coordinate(d, lo[du]) <= b.min[d] && b.max[d] <= grid_.coordinate(d, hi[du]))) return false;
    }
    return fields_[static_cast<std::size_t>(axis_index(axis))].count_forbidden(lo, hi) == 0;
  }

  //! Moves each side in to the bounding box of the covered faces when no
  //! covered face is lost (smaller boxes overlap less in later stages).
  void shrink_to_coverage(Box3& b, Axis axis) const {
    const std::vector<int> covered = index_.faces_covered(b, axis);
    Box3 tight{Vec3::Constant(kInf), Vec3::Constant(-kInf)};
    for (int f : covered) {
      tight.min = tight.min.cwiseMin(index_.face_box(f).min);
      tight.max = tight.max.cwiseMax(index_.face_box(f).max);
    }
    // Moving a side in never adds a covered face, and a covered face stays
    // in the closed box; it is lost only if it lies in the side's new plane
    // with the solid outside: only those faces need the exact test.
    for (int s = 0; s < 6; ++s) {
      const int dim = s / 2;
      Box3 candidate = b;
      if (s % 2)
        candidate.max[dim] = tight.max[dim];
      else
        candidate.min[dim] = tight.min[dim];
      if (candidate.min[dim] == b.min[dim] && candidate.max[dim] == b.max[dim]) continue;
      const double plane = (s % 2) ? candidate.max[dim] : candidate.min[dim];
      const bool keeps_all = std::all_of(covered.begin(), covered.end(), [&](int f) {
        const Box3& fb = index_.face_box(f);
        return !(fb.min[dim] == plane && fb.max[dim] == plane) || index_.face_covered(f, candidate, axis);
      });
      if (keeps_all) b = candidate;
    }
  }

  const SolidIndex& index_;
  const std::array<HeightField, 6>& fields_;
  const GridGeometry& grid_;
  SizeLimits limits_;
  bool maximal_;
  bool fields_describe_mesh_;
  Box3 domain_;
};

//! Axes a face can be milled from (exact n.d >= 0), the closest first.
std::vector<Axis> candidate_axes(const SolidIndex& index, int face) {
  const Vec3 n = face_unit_normal(index.mesh(), static_cast<std::size_t>(face));
  std::vector<Axis> axes;
  axes.push_back(closest_axis(n));
  std::vector<std::pair<double, Axis>> rest;
  for (Axis a : kAllAxes)
    if (a != axes[0] && index.facing_sign(face, a) >= 0) rest.emplace_back(-n.dot(axis_direction(a)), a);
  std::stable_sort(rest.begin(), rest.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  if (index.facing_sign(face, axes[0]) < 0) axes.clear();
  for (const auto& r : rest) axes.push_back(r.second);
  return axes;
}

Vec3 centroid(const Mesh& mesh, int f) {
  const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
  return (mesh.vertices[static_cast<std::size_t>(t[0])] + mesh.vertices[static_cast<std::size_t>(t[1])] +
          mesh.vertices[static_cast<std::size_t>(t[2])]) /
         3.0;
}

//! A face that shares an edge with a neighbour such that no axis the face
//! faces is faced by the neighbour too, and the edge lies in no axis-aligned
//! plane, can never lie in a valid box: the interior of the edge would be
//! inside the open box and so would the neighbour near it. Refinement cannot
//! help (the children along the edge inherit the problem). Returns a
//! description of the first such crease among `faces`, or "" if none.
std::string impossible_crease(const SolidIndex& index, const std::vector<int>& faces,
                              const std::vector<int>& parent_face) {
  const Mesh& mesh = index.mesh();
  std::unordered_map<std::uint64_t, int> directed;  // (from, to) -> face
  auto key = [](int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
  };
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Triangle& t = mesh.faces[f];
    for (int e = 0; e < 3; ++e) directed.emplace(key(t[e], t[(e + 1) % 3]), static_cast<int>(f));
  }
  for (int f : faces) {
    const Triangle& t = mesh.faces[static_cast<std::size_t>(f)];
    for (int e = 0; e < 3; ++e) {
      const int u = t[e], v = t[(e + 1) % 3];
      const Vec3& pu = mesh.vertices[static_cast<std::size_t>(u)];
      const Vec3& pv = mesh.vertices[static_cast<std::size_t>(v)];
      if (pu.x() == pv.x() || pu.y() == pv.y() || pu.z() == pv.z()) continue;
      const auto it = directed.find(key(v, u));
      if (it == directed.end()) continue;
      const int g = it->second;
      bool common = false;
      for (Axis a : kAllAxes) common = common || (index.facing_sign(f, a) >= 0 && index.facing_sign(g, a) >= 0);
      if (common) continue;
      const Vec3 nf = face_unit_normal(mesh, static_cast<std::size_t>(f));
      const Vec3 ng = face_unit_normal(mesh, static_cast<std::size_t>(g));
      const double angle = std::acos(std::clamp(nf.dot(ng), -1.0, 1.0)) * 180.0 / M_PI;
      std::ostringstream msg;
      msg << "cannot cover face " << parent_face[static_cast<std::size_t>(f)] << " of the input: its edge with face "
          << parent_face[static_cast<std::size_t>(g)] << " (between (" << pu.transpose() << ") and ("
          << pv.transpose() << ")) is a crease whose two sides no axis-aligned milling direction sees together "
          << "(normals " << angle << " degrees apart, edge not axis-aligned), so no valid height-field box can "
          << "contain it and local refinement cannot help; smooth or repair the mesh there (a fold or a very "
          << "thin groove/fin)";
      return msg.str();
    }
  }
  return {};
}

void check_options(const GrowOptions& o) {
  if (!(o.grid_factor > 0) || !std::isfinite(o.grid_factor))
    throw InvalidArgumentError("grid factor must be a positive number (got " + std::to_string(o.grid_factor) + ")");
  if (!(o.max_height > 0))
    throw InvalidArgumentError("maximum block height must be positive (got " + std::to_string(o.max_height) + ")");
  for (int k = 0; k < 3; ++k)
    if (!(o.machine_size[k] > 0))
      throw InvalidArgumentError("machine size must be positive in x, y and z (got " +
                                 std::to_string(o.machine_size[k]) + ")");
  if (o.batch_size < 1) throw InvalidArgumentError("batch size must be at least 1");
  if (o.strategies.empty()) throw InvalidArgumentError("grow_boxes needs at least one growth strategy");
  if (o.max_refinement_levels < 0) throw InvalidArgumentError("max refinement levels must be >= 0");
}

//! Blocks per box: connected surface pieces inside it (box_pieces.h).
void count_pieces(const SolidIndex& index, GrowResult& result) {
  const std::vector<int> neighbours = detail::face_neighbours(index.mesh());
  result.num_pieces.assign(result.boxes.size(), 1);
  parallel_for(0, result.boxes.size(), [&](std::size_t i) {
    const auto pieces = detail::surface_pieces(index, neighbours, result.boxes[i]);
    result.num_pieces[i] = std::max<int>(1, static_cast<int>(pieces.size()));
  });
}

}  // namespace

GrowResult grow_boxes(const Mesh& mesh, const GrowOptions& options) {
  check_options(options);
  if (mesh.empty()) throw InvalidMeshError("grow_boxes: the mesh has no faces");
  std::array<HeightField, 6> own_fields;
  if (!options.fields)
    own_fields = compute_fields(mesh, FieldOptions{.grid_factor = options.grid_factor,
                                                   .max_overhang_deg = options.max_overhang_deg,
                                                   .allowed_overhangs = options.allowed_overhangs,
                                                   .progress = nullptr});
  if (options.allowed_overhangs && options.allowed_overhangs->size() != mesh.num_faces())
    throw InvalidArgumentError("grow_boxes: one overhang allowance per face expected");
  // The allowances of the current (refined) mesh: a face inherits its parent's.
  const auto allowances_of = [&](const GrowResult& r) {
    std::vector<std::uint8_t> a;
    if (!options.allowed_overhangs) return a;
    a.reserve(r.parent_face.size());
    for (int parent : r.parent_face) a.push_back((*options.allowed_overhangs)[static_cast<std::size_t>(parent)]);
    return a;
  };
  // Their base floors (a part of a face lies no higher than the face).
  if (options.overhang_floors && (!options.allowed_overhangs || options.overhang_floors->size() != mesh.num_faces()))
    throw InvalidArgumentError("grow_boxes: base floors need the allowances, one per face");
  const auto floors_of = [&](const GrowResult& r) {
    std::vector<std::array<double, 3>> a;
    if (!options.overhang_floors) return a;
    a.reserve(r.parent_face.size());
    for (int parent : r.parent_face) a.push_back((*options.overhang_floors)[static_cast<std::size_t>(parent)]);
    return a;
  };
  const std::array<HeightField, 6>& fields = options.fields ? *options.fields : own_fields;
  const SizeLimits limits{options.max_height, options.machine_size};
  const double sine = overhang_sine(options.max_overhang_deg);
  Progress* progress = options.progress;

  GrowResult result;
  result.mesh = mesh;
  result.parent_face.resize(mesh.faces.size());
  std::iota(result.parent_face.begin(), result.parent_face.end(), 0);
  std::vector<Vec3> seed_points;  // centroids of all seeds so far (farthest-point order)

  for (int level = 0;; ++level) {
    const std::vector<std::uint8_t> allowed = allowances_of(result);
    const std::vector<std::array<double, 3>> floors = floors_of(result);
    const SolidIndex index(result.mesh, sine, options.allowed_overhangs ? &allowed : nullptr,
                           options.overhang_floors ? &floors : nullptr);
    const Grower grower(index, fields, limits, true, level == 0);
    const int nf = index.num_faces();
    // Boxes from before a refinement stay valid (same surface); re-check
    // exactly anyway since midpoints are rounded.
    if (level > 0) {
      std::vector<HeightBox> kept;
      for (const HeightBox& hb : result.boxes)
        if (index.box_is_valid(hb)) kept.push_back(hb);
      result.boxes = std::move(kept);
      result.covered.clear();  // recomputed on the final mesh
    }
    // Boxes carried over from an earlier decomposition: candidates from the
    // start where they are still valid (exact), within the limits and
    // covering a face (their seed: the first one, set below; the earlier
    // mesh's face ids need not be this one's).
    if (level == 0 && options.carried) {
      std::vector<char> keep(options.carried->size(), 0);
      parallel_for(0, options.carried->size(), [&](std::size_t i) {
        const HeightBox& hb = (*options.carried)[i];
        keep[i] = limits.fits(hb.box, hb.axis) && index.box_is_valid(hb);
      });
      for (std::size_t i = 0; i < keep.size(); ++i)
        if (keep[i]) result.boxes.push_back(HeightBox{(*options.carried)[i].box, (*options.carried)[i].axis, -1});
    }
    std::vector<char> covered(static_cast<std::size_t>(nf), 0);
    std::size_t num_covered = 0;
    auto mark = [&](const std::vector<int>& faces) {
      for (int f : faces)
        if (!covered[static_cast<std::size_t>(f)]) {
          covered[static_cast<std::size_t>(f)] = 1;
          ++num_covered;
        }
    };
    {
      std::vector<std::vector<int>> lists(result.boxes.size());
      parallel_for(0, result.boxes.size(), [&](std::size_t i) { lists[i] = index.faces_covered(result.boxes[i]); });
      for (const auto& l : lists) mark(l);
      if (level == 0) {  // the carried boxes (valid lists while the mesh is not refined)
        std::vector<HeightBox> kept;
        for (std::size_t i = 0; i < lists.size(); ++i)
          if (!lists[i].empty()) {
            kept.push_back(HeightBox{result.boxes[i].box, result.boxes[i].axis, lists[i].front()});
            result.covered.push_back(std::move(lists[i]));
          }
        result.boxes = std::move(kept);
      }
    }
    std::vector<double> dist2(static_cast<std::size_t>(nf), kInf);
    std::vector<Vec3> centres(static_cast<std::size_t>(nf));
    for (int f = 0; f < nf; ++f) centres[static_cast<std::size_t>(f)] = centroid(result.mesh, f);
    auto add_seed_point = [&](const Vec3& p) {
      seed_points.push_back(p);
      for (int f = 0; f < nf; ++f)
        dist2[static_cast<std::size_t>(f)] =
            std::min(dist2[static_cast<std::size_t>(f)], (centres[static_cast<std::size_t>(f)] - p).squaredNorm());
    };
    {
      const std::vector<Vec3> previous = std::move(seed_points);
      seed_points.clear();
      for (const Vec3& p : previous) add_seed_point(p);
    }
    std::vector<char> failed(static_cast<std::size_t>(nf), 0);
    if (progress) progress->update(num_covered, static_cast<std::size_t>(nf));

    for (;;) {
      // a. Seeds: farthest uncovered faces from all previous seeds.
      std::vector<int> batch;
      for (int k = 0; k < options.batch_size; ++k) {
        int pick = -1;
        for (int f = 0; f < nf; ++f) {
          if (covered[static_cast<std::size_t>(f)] || failed[static_cast<std::size_t>(f)]) continue;
          if (pick < 0 || dist2[static_cast<std::size_t>(f)] > dist2[static_cast<std::size_t>(pick)]) pick = f;
        }
        if (pick < 0) break;
        batch.push_back(pick);
        failed[static_cast<std::size_t>(pick)] = 2;  // taken (reset below when it grows)
        add_seed_point(centres[static_cast<std::size_t>(pick)]);
      }
      if (batch.empty()) break;
      ++result.num_rounds;
      result.num_seeds += static_cast<int>(batch.size());
      // b. Grow in parallel (one slot per seed).
      std::vector<std::vector<HeightBox>> grown(batch.size());
      std::vector<std::vector<std::vector<int>>> grown_cover(batch.size());
      parallel_for(0, batch.size(), [&](std::size_t i) {
        const int f = batch[i];
        for (Axis a : candidate_axes(index, f)) {
          for (GrowStrategy strategy : options.strategies) {
            const auto box = grower.grow(f, a, strategy);
            if (!box) continue;
            const bool duplicate = std::any_of(grown[i].begin(), grown[i].end(), [&](const HeightBox& g) {
              return g.axis == a && g.box.min == box->min && g.box.max == box->max;
            });
            if (duplicate) continue;
            grown[i].push_back(HeightBox{*box, a, f});
            grown_cover[i].push_back(index.faces_covered(*box, a));
          }
          if (!options.all_axes && !grown[i].empty()) return;
        }
      });
      // c. Coverage, in seed order.
      for (std::size_t i = 0; i < batch.size(); ++i) {
        failed[static_cast<std::size_t>(batch[i])] = grown[i].empty() ? 1 : 0;
        for (std::size_t k = 0; k < grown[i].size(); ++k) {
          result.boxes.push_back(grown[i][k]);
          result.covered.push_back(grown_cover[i][k]);  // valid while the mesh is not refined
          mark(grown_cover[i][k]);
        }
      }
      if (progress) progress->update(num_covered, static_cast<std::size_t>(nf));
    }

    std::vector<int> uncovered;
    for (int f = 0; f < nf; ++f)
      if (!covered[static_cast<std::size_t>(f)]) uncovered.push_back(f);
    if (uncovered.empty()) break;
    if (const std::string why = impossible_crease(index, uncovered, result.parent_face); !why.empty())
      throw AlgorithmError(why);
    if (level >= options.max_refinement_levels) {
      const int f = uncovered.front();
      std::ostringstream msg;
      msg << "cannot cover face " << result.parent_face[static_cast<std::size_t>(f)] << " of the input (and "
          << uncovered.size() - 1 << " other faces) with a valid height-field box even after "
          << options.max_refinement_levels
          << " rounds of local refinement: a triangle facing away from every direction it could be milled from "
             "crosses its bounding box (a feature thinner than the triangles; the mesh may self-intersect)";
      throw AlgorithmError(msg.str());
    }
    RefineResult refined = refine_mesh(result.mesh, uncovered);
    const int num_split = refined.num_split_1to4 + refined.num_split_1to2;
    result.num_refined_faces += num_split;
    if (progress) {
      std::ostringstream msg;
      msg << uncovered.size() << " faces cannot be covered by a valid box (thin features): refined locally ("
          << refined.num_split_1to4 << " faces split 1-to-4, " << refined.num_split_1to2 << " split 1-to-2)";
      progress->warn(msg.str());
    }
    std::vector<int> parent(refined.parent.size());
    for (std::size_t f = 0; f < parent.size(); ++f)
      parent[f] = result.parent_face[static_cast<std::size_t>(refined.parent[f])];
    result.parent_face = std::move(parent);
    result.mesh = std::move(refined.mesh);
  }

  // Final coverage lists on the final mesh; identical boxes kept once.
  {
    const bool lists_current = result.num_refined_faces == 0 && result.covered.size() == result.boxes.size();
    std::vector<HeightBox> unique;
    std::vector<std::vector<int>> unique_covered;
    for (std::size_t i = 0; i < result.boxes.size(); ++i) {
      const HeightBox& hb = result.boxes[i];
      const bool duplicate = std::any_of(unique.begin(), unique.end(), [&](const HeightBox& u) {
        return u.axis == hb.axis && u.box.min == hb.box.min && u.box.max == hb.box.max;
      });
      if (duplicate) continue;
      unique.push_back(hb);
      if (lists_current) unique_covered.push_back(std::move(result.covered[i]));
    }
    result.boxes = std::move(unique);
    const std::vector<std::uint8_t> allowed = allowances_of(result);
    const std::vector<std::array<double, 3>> floors = floors_of(result);
    const SolidIndex index(result.mesh, sine, options.allowed_overhangs ? &allowed : nullptr,
                           options.overhang_floors ? &floors : nullptr);
    if (lists_current) {
      result.covered = std::move(unique_covered);
    } else {
      result.covered.assign(result.boxes.size(), {});
      parallel_for(0, result.boxes.size(),
                   [&](std::size_t i) { result.covered[i] = index.faces_covered(result.boxes[i]); });
    }
    count_pieces(index, result);
  }
  if (progress) {
    std::ostringstream msg;
    msg << result.boxes.size() << " boxes grown from " << result.num_seeds << " seeds in " << result.num_rounds
        << " rounds";
    progress->info(msg.str());
  }
  return result;
}

}  // namespace subfab
