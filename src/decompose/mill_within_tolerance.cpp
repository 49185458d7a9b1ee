// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/mill_within_tolerance.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "decompose/block_pairs_detail.h"
#include "geometry/solid_index.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/geometry/axis.h"
#include "subfab/validate/fill_deviation_lower_bound.h"
#include "subfab/validate/fill_deviation_upper_bound.h"
#include "subfab/validate/measure_fill_deviation.h"
#include "subfab/validate/milled_shape.h"
#include "subfab/validate/validate_decomposition.h"
#include "validate/validate_booleans.h"

namespace subfab {
namespace {


std::string format_length(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

//! A hash of the mesh's bytes (vertices, then faces), combined with `seed`.
std::uint64_t hash_mesh(const Mesh& m, std::uint64_t seed = 0) {
  const auto bytes = [](const auto& v) {
    return std::hash<std::string_view>{}(
        std::string_view(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(v.front())));
  };
  return (seed * 1099511628211ull ^ bytes(m.vertices)) * 1099511628211ull ^ bytes(m.faces);
}

bool same_bytes(const Mesh& a, const Mesh& b) {
  return a.vertices.size() == b.vertices.size() && a.faces.size() == b.faces.size() &&
         std::memcmp(a.vertices.data(), b.vertices.data(), a.vertices.size() * sizeof(Vec3)) == 0 &&
         std::memcmp(a.faces.data(), b.faces.data(), a.faces.size() * sizeof(Triangle)) == 0;
}

}  // namespace

struct MillCache::Impl {
  //! One block and what step 1 and step 3a made of it.
  struct Entry {
    Mesh block;                 // the carved block, as given
    Axis axis = Axis::PosZ;
    std::string failure;        // step 1's failure (no closed height field, or not computed)
    char filled = 0;
    Mesh milled;                // its milled shape (when filled)
    std::optional<std::vector<BoundingBox>> fill;
    std::vector<BoundingBox> columns;
    bool complete = false;       // step 1 filled it in (an entry made by a call that threw is not)
    bool outside_known = false;  // step 3a ran on it: `outside` is its result (nullopt: it threw)
    std::optional<detail::OutsidePart> outside;
  };
  bool bound = false;
  std::uint64_t solid_key = 0;
  std::unordered_multimap<std::uint64_t, std::shared_ptr<Entry>> entries;
  std::size_t hits = 0;

  static std::uint64_t key(const Mesh& block, Axis axis) {
    return hash_mesh(block, static_cast<std::uint64_t>(axis) + 1);
  }
  //! Binds the cache to `solid`, emptying it when it held another.
  void bind(const Mesh& solid) {
    const std::uint64_t k = hash_mesh(solid);
    if (bound && k == solid_key) return;
    entries.clear();
    bound = true;
    solid_key = k;
  }
  std::shared_ptr<Entry> find(const Mesh& block, Axis axis, std::uint64_t k) const {
    const auto [begin, end] = entries.equal_range(k);
    for (auto it = begin; it != end; ++it)
      if (it->second->complete && it->second->axis == axis && same_bytes(it->second->block, block)) return it->second;
    return nullptr;
  }
};

MillCache::MillCache() : impl_(std::make_unique<Impl>()) {}
MillCache::~MillCache() = default;
std::size_t MillCache::size() const { return impl_->entries.size(); }
std::size_t MillCache::hits() const { return impl_->hits; }

std::size_t MillToleranceResult::num_failed() const {
  return static_cast<std::size_t>(
      std::count_if(failures.begin(), failures.end(), [](const std::string& f) { return !f.empty(); }));
}

MillToleranceResult mill_within_tolerance(const Mesh& solid, std::vector<Block> blocks,
                                          const MillToleranceOptions& options) {
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
    throw InvalidArgumentError("mill_within_tolerance: the tolerance must be positive");
  if (!(options.error_fraction > 0 && options.error_fraction < 1))
    throw InvalidArgumentError("mill_within_tolerance: error_fraction must be in (0, 1)");
  Progress* progress = options.progress;
  const std::size_t n = blocks.size();
  if (options.measure && (options.measure->size() != n || !options.known_deviation ||
                          options.known_deviation->size() != n))
    throw InvalidArgumentError("mill_within_tolerance: measure and known_deviation must have one entry per block");
  MillToleranceResult r;
  r.filled.assign(n, 0);
  r.failures.assign(n, std::string());
  r.deviation.assign(n, 0.0);
  r.far_points.assign(n, {});
  r.collided.assign(n, 0);

  // 0. the blocks milled before on this solid (options.cache)
  using Entry = MillCache::Impl::Entry;
  std::vector<std::shared_ptr<Entry>> entry(n);  // per block: its cache entry (found, or made below)
  std::vector<char> hit(n, 0);
  std::size_t num_hits = 0;
  if (options.cache) {
    MillCache::Impl& cache = options.cache->impl();
    cache.bind(solid);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t k = MillCache::Impl::key(blocks[i].mesh, blocks[i].axis);
      entry[i] = cache.find(blocks[i].mesh, blocks[i].axis, k);
      if (entry[i]) {
        hit[i] = 1;
        ++num_hits;
        continue;
      }
      entry[i] = std::make_shared<Entry>();
      entry[i]->block = blocks[i].mesh;
      entry[i]->axis = blocks[i].axis;
      cache.entries.emplace(k, entry[i]);
    }
    cache.hits += num_hits;
  }

  // 1. milled shapes, and the boxes that cover what they add (fill_columns())
  std::atomic<std::size_t> done{0};
  std::vector<std::optional<std::vector<BoundingBox>>> fill(n);
  std::vector<std::vector<BoundingBox>> columns(n);  // the finer cover before the tiling (fill_face_columns())
  parallel_for(0, n, [&](std::size_t i) {
    if (hit[i]) {
      const Entry& e = *entry[i];
      r.failures[i] = e.failure;
      if (e.filled) {
        fill[i] = e.fill;
        columns[i] = e.columns;
        blocks[i].mesh = e.milled;
        r.filled[i] = 1;
      }
      if (progress) progress->update(++done, 2 * n);
      return;
    }
    const Vec3 d = axis_direction(blocks[i].axis);
    try {
      MilledShape m = milled_shape(blocks[i].mesh, d);
      if (!m.is_block) {
        if (!check_closed_solid(m.mesh).ok() || !is_height_field(m.mesh, d))
          r.failures[i] = "its milled shape is not a closed 2-manifold height field";
        else {
          std::optional<std::vector<BoundingBox>> faces = fill_face_columns(blocks[i].mesh, m.mesh, blocks[i].axis);
          if (faces) {
            fill[i] = tile_columns(*faces, m.mesh, blocks[i].axis);
            columns[i] = std::move(*faces);
          }
          blocks[i].mesh = std::move(m.mesh);
          r.filled[i] = 1;
        }
      }
    } catch (const std::exception& e) {
      r.failures[i] = std::string("its milled shape could not be computed: ") + e.what();
    }
    if (entry[i]) {  // a new cache entry: what this step made of the block
      Entry& e = *entry[i];
      e.complete = true;
      e.failure = r.failures[i];
      e.filled = r.filled[i];
      if (r.filled[i]) {
        e.milled = blocks[i].mesh;
        e.fill = fill[i];
        e.columns = columns[i];
      }
    }
    if (progress) progress->update(++done, 2 * n);
  });
  if (progress && options.cache)
    progress->info(std::to_string(num_hits) + " of " + std::to_string(n) +
                   " block(s) milled before, unchanged: their milled shapes reused");

  // 2. collisions of the filled blocks with every other block
  std::vector<BoundingBox> boxes(n);
  std::vector<double> volumes(n);
  parallel_for(0, n, [&](std::size_t i) {
    boxes[i] = bounding_box(blocks[i].mesh);
    volumes[i] = signed_volume(blocks[i].mesh);
  });
  // The carved blocks do not overlap, so two milled shapes M_i = C_i + G_i
  // and M_j can overlap only where a fill G meets the other shape: a pair
  // none of whose fill boxes (fill_columns(), covering G) meets the other's
  // box in its interior cannot collide (max planck at 3.3e-3: the exact
  // checks had been 33 of its mill stages' 58 s).
  // The overlap then lies in the box around those meetings (`region`): the
  // exact check clips both shapes near it (their shared cut faces elsewhere
  // cost the corefinement most: max planck at 3.3e-3, 40 % of the run).
  const auto extend_by_fill = [&](std::size_t k, const BoundingBox& other, BoundingBox& region) {
    if (!r.filled[k]) return;
    if (!fill[k]) {  // the fill is not bounded: the whole shape
      region.extend(boxes[k].min.cwiseMax(other.min));
      region.extend(boxes[k].max.cwiseMin(other.max));
      return;
    }
    detail::extend_by_fill_boxes(*fill[k], other, region);
  };
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  std::vector<BoundingBox> regions;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!(r.filled[i] || r.filled[j]) || !detail::interiors_meet(boxes[i], boxes[j])) continue;
      BoundingBox region;
      extend_by_fill(i, boxes[j], region);
      extend_by_fill(j, boxes[i], region);
      if (region.is_empty()) continue;
      pairs.emplace_back(i, j);
      regions.push_back(region);
    }
  // A bound from the boxes first (blocks meeting on a plane of the frame).
  std::vector<char> unsettled(pairs.size(), 0);
  parallel_for(0, pairs.size(), [&](std::size_t p) {
    const auto [i, j] = pairs[p];
    const double allowed = options.collision_tolerance * std::min(volumes[i], volumes[j]);
    unsettled[p] = overlap_volume_bound(blocks[i].mesh, blocks[j].mesh, Eigen::Matrix3d::Identity()) > allowed ? 1 : 0;
  });
  // Most of the others do not collide either (max planck and bimba: 1 of
  // 137): their shapes are proven apart without a boolean where the
  // interior of each misses every fill box of the other
  // (detail::fill_misses_solid()).
  std::vector<std::unique_ptr<detail::SolidIndex>> index(n);
  {
    std::vector<char> used(n, 0);
    for (std::size_t p = 0; p < pairs.size(); ++p)
      if (unsettled[p]) {
        const auto [i, j] = pairs[p];
        if (r.filled[i]) used[j] = 1;  // the other's interior against a block's fill
        if (r.filled[j]) used[i] = 1;
      }
    parallel_for(0, n, [&](std::size_t k) {
      if (used[k]) index[k] = detail::inside_test_index(blocks[k].mesh);
    });
  }
  const auto fill_misses = [&](std::size_t k, std::size_t other) {
    if (!r.filled[k]) return true;
    if (!fill[k] || !index[other]) return false;
    // the tiles first, then (a neighbour's face crossing a tile) every column
    return detail::fill_misses_solid(*fill[k], *index[other], boxes[other]) ||
           detail::fill_misses_solid(columns[k], *index[other], boxes[other]);
  };
  std::vector<char> collides(pairs.size(), 0);
  std::atomic<std::size_t> num_exact{0};
  parallel_for(0, pairs.size(), [&](std::size_t p) {
    if (!unsettled[p]) return;
    const auto [i, j] = pairs[p];
    if (fill_misses(i, j) && fill_misses(j, i)) return;
    ++num_exact;
    const double allowed = options.collision_tolerance * std::min(volumes[i], volumes[j]);
    try {
      collides[p] = detail::exact_blocks_overlap(blocks[i].mesh, blocks[j].mesh, regions[p]) > allowed ? 1 : 0;
    } catch (const std::exception&) {
      collides[p] = 1;
    }
  });
  if (progress && !pairs.empty())
    progress->info(std::to_string(pairs.size()) + " pair(s) of blocks a fill reaches: " +
                   std::to_string(pairs.size() - static_cast<std::size_t>(std::count(unsettled.begin(), unsettled.end(), 1))) +
                   " apart by their boxes, " +
                   std::to_string(static_cast<std::size_t>(std::count(unsettled.begin(), unsettled.end(), 1)) - num_exact) +
                   " proven apart by their fill boxes, " + std::to_string(num_exact.load()) + " checked exactly, " +
                   std::to_string(std::count(collides.begin(), collides.end(), 1)) + " colliding");
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (!collides[p]) continue;
    const auto [i, j] = pairs[p];
    r.collided[i] = r.collided[j] = 1;
    for (const auto& [a, b] : {std::pair{i, j}, std::pair{j, i}})
      if (r.filled[a] && r.failures[a].empty())
        r.failures[a] = "its milled shape overlaps block " + std::to_string(b + 1);
  }

  // 2b. a sampled lower bound of each filled block's deviation
  //     (fill_deviation_lower_bound.h): a point of the model made farther
  //     than T from the input fails the block for sure, without the exact
  //     measure (the same blocks fail as with it; ladder candidates and
  //     rounds far beyond T cost seconds instead of a minute).
  {
    std::vector<const Mesh*> meshes;
    std::vector<std::optional<std::vector<BoundingBox>>> boxes_of;
    std::vector<char> which;
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < n; ++i) {
      if (!r.filled[i]) continue;
      ids.push_back(i);
      meshes.push_back(&blocks[i].mesh);
      boxes_of.push_back(fill[i]);
      which.push_back(r.failures[i].empty() && !(options.measure && !(*options.measure)[i]) ? 1 : 0);
    }
    if (std::count(which.begin(), which.end(), char{1}) > 0) {
      const bool locate = options.locate_failures && !options.stop_at_first_failure;
      std::vector<std::vector<Vec3>> far;
      const std::vector<double> low =
          fill_deviation_lower_bounds(solid, meshes, boxes_of, options.tolerance, which, locate ? &far : nullptr);
      for (std::size_t k = 0; k < ids.size(); ++k)
        if (which[k] && low[k] > options.tolerance) {
          if (locate) r.far_points[ids[k]] = std::move(far[k]);
          r.failures[ids[k]] = "its milled shape deviates at least " + format_length(low[k]) +
                               " (a sampled point) > the tolerance " + format_length(options.tolerance);
          r.stopped = options.stop_at_first_failure;
        }
    }
  }
  if (r.stopped) {
    for (std::size_t i = 0; i < n; ++i)
      if (r.filled[i] && r.failures[i].empty()) r.failures[i] = "not measured: another block fails";
    r.blocks = std::move(blocks);
    if (progress)
      progress->info(std::to_string(r.num_failed()) + " of " + std::to_string(n) +
                     " blocks rejected: a sampled point of a milled shape lies beyond the tolerance, nothing measured");
    return r;
  }

  // 3. the deviation near every filled block, the others that stick out
  //    included: in the boxes that cover its fill (one task per box, all
  //    blocks' boxes in one parallel loop: a big block has many), or near
  //    the columns of the whole block when fill_columns() could not bound the fill.
  const FillDeviationMeter meter(solid);
  std::vector<const Mesh*> all_filled;
  for (std::size_t i = 0; i < n; ++i)
    if (r.filled[i]) all_filled.push_back(&blocks[i].mesh);
  const double error = options.error_fraction * options.tolerance;
  const FillDeviationOptions fo{.reach = options.tolerance, .error = error, .max_faces = options.max_region_faces};
  std::vector<char> known(n, 0);  // filled, passing, and its deviation known (options.measure)
  for (std::size_t i = 0; i < n; ++i)
    if (r.filled[i] && r.failures[i].empty() && options.measure && !(*options.measure)[i]) known[i] = 1;
  // 3a. first the bound over each block's part outside the solid
  //     (fill_deviation_upper_bound.h: an exact difference, then distances
  //     over its faces, within the same error as the measure); a block it
  //     keeps within the tolerance is not measured in regions.
  std::vector<char> cleared(n, 0);
  std::vector<double> cleared_bound(n, 0.0);
  {
    std::vector<std::size_t> slot(n, n);  // block -> its index in all_filled
    for (std::size_t i = 0, k = 0; i < n; ++i)
      if (r.filled[i]) slot[i] = k++;
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < n; ++i)
      if (r.filled[i] && r.failures[i].empty() && !known[i]) ids.push_back(i);
    // The differences run one per block in parallel; a lone block's runs on
    // one core while its regions' measure runs on all (hu at 1.4e-3, one
    // block: difference 11 s and distances 10 s against regions 9 s).
    if (ids.size() < 2) ids.clear();
    std::vector<std::optional<detail::OutsidePart>> parts(ids.size());
    // Each part lies in its block's fill boxes: the difference sees only the
    // block's faces near them (the box around them, widened by a margin so
    // that no plane of it is a face's).
    parallel_for(0, ids.size(), [&](std::size_t k) {
      if (entry[ids[k]] && entry[ids[k]]->outside_known) {
        parts[k] = entry[ids[k]]->outside;
        return;
      }
      std::optional<BoundingBox> within;
      if (fill[ids[k]] && !fill[ids[k]]->empty()) within = detail::fill_hull(*fill[ids[k]], boxes[ids[k]]);
      try {
        parts[k] = detail::outside_part(blocks[ids[k]].mesh, solid, within ? &*within : nullptr);
      } catch (const std::exception&) {
        // no part: measured in regions
      }
    });
    for (std::size_t k = 0; k < ids.size(); ++k)
      if (entry[ids[k]] && !entry[ids[k]]->outside_known) {
        entry[ids[k]]->outside = parts[k];
        entry[ids[k]]->outside_known = true;
      }
    std::vector<FillPart> view(all_filled.size());
    for (std::size_t k = 0; k < ids.size(); ++k)
      if (parts[k]) view[slot[ids[k]]] = {parts[k]->faces(), &parts[k]->on_input};
    FillDeviationUpperBounds upper;
    try {
      upper = fill_deviation_upper_bounds(solid, all_filled, view, {.error = error, .stop = options.tolerance});
    } catch (const std::exception&) {
      upper.blocks.assign(all_filled.size(), {});
    }
    for (std::size_t i : ids)
      if (upper.blocks[slot[i]].bound() <= options.tolerance) {
        cleared[i] = 1;
        cleared_bound[i] = upper.blocks[slot[i]].bound();
        ++r.num_bounded;
      }
  }
  std::vector<std::size_t> measured_ids;
  std::vector<const Mesh*> measured_blocks;
  std::vector<std::optional<std::vector<BoundingBox>>> measured_fills;
  std::size_t num_regions = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!r.filled[i] || !r.failures[i].empty() || known[i] || cleared[i]) continue;
    measured_ids.push_back(i);
    measured_blocks.push_back(&blocks[i].mesh);
    measured_fills.push_back(std::move(fill[i]));
    num_regions += measured_fills.back() ? measured_fills.back()->size() : 1;
  }
  if (progress)
    progress->info(std::to_string(r.num_bounded) + " filled block(s) within the tolerance by the bound over their parts "
                   "outside the input; measuring the deviation in " + std::to_string(num_regions) + " region(s) of " +
                   std::to_string(measured_ids.size()) + " of " + std::to_string(all_filled.size()) + " filled block(s)" +
                   (options.measure ? " (" + std::to_string(std::count(known.begin(), known.end(), char{1})) +
                                          " known from before: nothing near them changed)"
                                    : std::string()));
  const std::vector<FillDeviation> measured =
      measure_fills(meter, measured_blocks, measured_fills, all_filled, fo, [&](std::size_t d, std::size_t total) {
        if (progress) progress->update(n + (n * d) / std::max<std::size_t>(total, 1), 2 * n);
      });
  std::vector<FillDeviation> deviation(n);
  for (std::size_t k = 0; k < measured_ids.size(); ++k) deviation[measured_ids[k]] = measured[k];
  for (std::size_t i = 0; i < n; ++i) {
    if (known[i]) {
      r.deviation[i] = (*options.known_deviation)[i];
    } else if (cleared[i]) {
      r.deviation[i] = cleared_bound[i];
    } else if (r.filled[i] && r.failures[i].empty()) {
      const FillDeviation& dev = deviation[i];
      if (!dev.failure.empty())
        r.failures[i] = "its deviation could not be measured: " + dev.failure;
      else if (dev.bound() > options.tolerance)
        r.failures[i] = "its milled shape deviates up to " + format_length(dev.bound()) + " > the tolerance " +
                        format_length(options.tolerance);
      else
        r.deviation[i] = dev.bound();
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (r.failures[i].empty()) r.max_deviation = std::max(r.max_deviation, r.deviation[i]);
  r.blocks = std::move(blocks);
  if (progress)
    progress->info(std::to_string(std::count(r.filled.begin(), r.filled.end(), 1)) + " of " + std::to_string(n) +
                   " blocks milled with filled undercuts, " + std::to_string(r.num_failed()) +
                   " beyond the tolerance");
  return r;
}

}  // namespace subfab
