// SPDX-License-Identifier: GPL-3.0-or-later
#include "mask_catalogue.h"

#include <algorithm>
#include <set>

namespace subfab::masks {
namespace {

int dot(const Offset& a, const Offset& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The pattern and POI sets of a base type, anchored at the origin.
Mask base_mask(const BaseType& t, int index) {
  Mask m;
  m.base_type = index;
  std::set<Offset> block;
  auto add_block = [&](const Offset& c) {
    for (int z = -1; z <= 1; ++z)
      for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) block.insert({c[0] + x, c[1] + y, c[2] + z});
  };
  add_block({0, 0, 0});
  if (t.kind == BaseType::Terrace) {
    auto in_region = [&](const Offset& p) {
      return std::all_of(t.region.begin(), t.region.end(), [&](const Offset& h) { return dot(h, p) >= 0; });
    };
    auto inside = [&](const Offset& p) { return dot(t.normal, p) <= (in_region(p) ? -1 : 0); };
    for (const Offset& p : block) m.signs.push_back({p, inside(p)});
    m.poi_sets.push_back({{0, 0, 0}});
    // The nearest upper-level points outside R (6-neighbours when there are
    // any, else 18-neighbours): each one is a POI set growing the lower level.
    for (int norm2 = 1; norm2 <= 3 && m.poi_sets.size() == 1; ++norm2)
      for (const Offset& b : block)
        if (dot(b, b) == norm2 && inside(b) && !in_region(b) && dot(t.normal, b) == 0) m.poi_sets.push_back({b});
    return m;
  }
  for (const Offset& p : t.points) add_block(p);
  const std::set<Offset> special(t.points.begin(), t.points.end());
  for (const Offset& p : block) {
    const bool plane = dot(t.normal, p) <= (t.kind == BaseType::Bump ? -1 : 0);
    m.signs.push_back({p, special.count(p) ? t.kind == BaseType::Bump : plane});
  }
  m.poi_sets.push_back(t.points);
  return m;
}

// Canonical form (sorted) for de-duplication.
Mask canonical(Mask m) {
  std::sort(m.signs.begin(), m.signs.end());
  for (auto& s : m.poi_sets) std::sort(s.begin(), s.end());
  std::sort(m.poi_sets.begin(), m.poi_sets.end());
  return m;
}

const std::vector<BaseType>& base_types_data() {
  static const std::vector<BaseType> kTypes = {
      // Several POI sets: terraces (step between two facets of one category
      // and a riser facet of another).
      {"A.1", BaseType::Terrace, {0, 0, 1}, {{1, 0, 0}}, {}},    // cat-1 levels, cat-2 riser
      {"A.2", BaseType::Terrace, {1, 0, 1}, {{0, 1, 0}}, {}},    // cat-2 levels, cat-1 riser
      {"A.3", BaseType::Terrace, {0, 0, 1}, {{1, 1, 0}, {1, 0, 0}}, {}},  // cat-1 levels, cat-3 riser end
      {"A.4", BaseType::Terrace, {1, 1, 1}, {{1, -1, 0}, {1, 0, 0}}, {}},  // cat-3 levels, cat-1 riser
      {"A.5", BaseType::Terrace, {1, 0, 1}, {{1, 0, -1}}, {}},   // cat-2 levels, cat-3 riser
      {"A.6", BaseType::Terrace, {1, 0, 1}, {{1, 1, 1}}, {}},    // cat-2 levels, cat-3 riser (other side)
      {"A.7", BaseType::Terrace, {1, 1, 1}, {{1, 0, 0}, {1, -1, 0}}, {}},  // cat-3 levels, cat-2 riser end
      // One POI set: pyramids.
      {"A.8", BaseType::Bump, {0, 0, 1}, {}, {{0, 0, 0}}},
      {"A.8", BaseType::Pit, {0, 0, 1}, {}, {{0, 0, 0}}},
      {"A.9", BaseType::Bump, {1, 0, 1}, {}, {{0, 0, 0}}},
      {"A.9", BaseType::Pit, {1, 0, 1}, {}, {{0, 0, 0}}},
      {"A.10", BaseType::Bump, {1, 1, 1}, {}, {{0, 0, 0}}},
      {"A.10", BaseType::Pit, {1, 1, 1}, {}, {{0, 0, 0}}},
      {"A.11", BaseType::Bump, {0, 0, 1}, {}, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
      {"A.11", BaseType::Pit, {0, 0, 1}, {}, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
  };
  return kTypes;
}

using Symmetry = std::pair<std::array<int, 3>, std::array<int, 3>>;  // axis permutation, signs

// The 48 signed permutation matrices (proper_only: the 24 rotations).
std::vector<Symmetry> cube_symmetries(bool proper_only) {
  std::vector<Symmetry> out;
  std::array<int, 3> perm{0, 1, 2};
  do {
    // Parity of the permutation.
    int inversions = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j) inversions += perm[static_cast<std::size_t>(i)] > perm[static_cast<std::size_t>(j)];
    for (int signs = 0; signs < 8; ++signs) {
      const int det = ((inversions % 2) ? -1 : 1) * (((signs & 1) ? -1 : 1) * ((signs & 2) ? -1 : 1) * ((signs & 4) ? -1 : 1));
      if (proper_only && det < 0) continue;
      out.push_back({perm, {(signs & 1) ? -1 : 1, (signs & 2) ? -1 : 1, (signs & 4) ? -1 : 1}});
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return out;
}

// Distinct images of each base type under the given symmetries.
std::vector<Mask> orbit_masks(const std::vector<Symmetry>& symmetries) {
    std::vector<Mask> out;
    const auto& types = base_types_data();
    for (std::size_t t = 0; t < types.size(); ++t) {
      const Mask base = base_mask(types[t], static_cast<int>(t));
      std::set<std::pair<std::vector<std::pair<Offset, bool>>, std::vector<std::vector<Offset>>>> seen;
      for (const auto& [p, s] : symmetries) {
        auto apply = [&](const Offset& o) {
          return Offset{s[0] * o[static_cast<std::size_t>(p[0])], s[1] * o[static_cast<std::size_t>(p[1])],
                        s[2] * o[static_cast<std::size_t>(p[2])]};
        };
        Mask m;
        m.base_type = base.base_type;
        for (const auto& [o, v] : base.signs) m.signs.push_back({apply(o), v});
        for (const auto& set : base.poi_sets) {
          std::vector<Offset> q;
          for (const Offset& o : set) q.push_back(apply(o));
          m.poi_sets.push_back(q);
        }
        m = canonical(m);
        if (seen.insert({m.signs, m.poi_sets}).second) {
          // Keep the base POI-set order (upper level first) for determinism.
          Mask ordered = m;
          ordered.poi_sets.clear();
          for (const auto& set : base.poi_sets) {
            std::vector<Offset> q;
            for (const Offset& o : set) q.push_back(apply(o));
            std::sort(q.begin(), q.end());
            ordered.poi_sets.push_back(q);
          }
          out.push_back(std::move(ordered));
        }
      }
    }
    return out;
}

}  // namespace

const std::vector<BaseType>& base_types() { return base_types_data(); }

const std::vector<Mask>& oriented_masks() {
  static const std::vector<Mask> kMasks = orbit_masks(cube_symmetries(false));
  return kMasks;
}

std::vector<std::size_t> rotation_classes_per_base_type() {
  std::vector<std::size_t> full(base_types().size(), 0), rotations(base_types().size(), 0), out;
  for (const Mask& m : oriented_masks()) ++full[static_cast<std::size_t>(m.base_type)];
  for (const Mask& m : orbit_masks(cube_symmetries(true))) ++rotations[static_cast<std::size_t>(m.base_type)];
  for (std::size_t t = 0; t < full.size(); ++t) out.push_back(full[t] / rotations[t]);
  return out;
}

std::vector<std::size_t> orientations_per_base_type() {
  std::vector<std::size_t> count(base_types().size(), 0);
  for (const Mask& m : oriented_masks()) ++count[static_cast<std::size_t>(m.base_type)];
  return count;
}

}  // namespace subfab::masks
