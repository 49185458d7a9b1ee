// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/hex/control_resolution.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numbers>

#include "subfab/hex/build_tubular_structure.h"
#include "subfab/hex/pillow_hex_mesh.h"
#include "subfab/hex/resample_skeleton.h"
#include "subfab/hex/scaled_jacobian.h"
#include "subfab/hex/subdivide_hex_mesh.h"
#include "support/hex_test_shapes.h"

namespace subfab {
namespace {

double min_sj(const HexMesh& m) {
  const auto sj = scaled_jacobians(m);
  return *std::min_element(sj.begin(), sj.end());
}

//! A straight tube of `layers` core hexahedra [-1, 1]^2 x [0, h] each,
//! padded, its padding out to [-2, 2]^2 on the sides and h/2 past the ends:
//! the ideal geometry of a padded tube (corners 0..3 of core hexahedron i
//! at its bottom, so face 1 is towards the next one).
HexMesh padded_tube(int layers, double h = 4.0) {
  HexMesh m = test::hex_grid(1, 1, layers);
  for (Vec3& p : m.vertices) p = Vec3(2 * p.x() - 1, 2 * p.y() - 1, h * p.z());
  const std::size_t core = m.vertices.size();
  const std::vector<int> outer = pillow_hex_mesh(m);
  const double top = h * layers;
  for (std::size_t v = 0; v < core; ++v) {
    if (outer[v] < 0) continue;
    const Vec3 p = m.vertices[v];
    const double z = p.z() < 1e-9 ? -h / 2 : p.z() > top - 1e-9 ? top + h / 2 : p.z();
    m.vertices[static_cast<std::size_t>(outer[v])] = Vec3(2 * p.x(), 2 * p.y(), z);
  }
  return m;
}

//! Runs every level of the plan with `offset` more splits.
HexMesh refine_all(const HexMesh& padded, const ResolutionPlan& plan, int offset) {
  int levels = 0;
  RefinementSchedule s = schedule_refinement(plan, offset, levels);
  HexMesh m = padded;
  for (int level = 1; level <= levels; ++level) {
    m = refine_hex_mesh(m, s, level);
    const HexMeshCheck c = check_hex_mesh(m);  // every level conforming
    EXPECT_TRUE(c.valid()) << "level " << level;
    EXPECT_EQ(c.num_unused_vertices, 0u);
  }
  return m;
}

// The template of Figure D.6 (1x1 -> 2x2) on an ideal padded tube, the cone
// in the middle layer, tip down: the tip side keeps its 6 hexahedra (core
// and 5 padding), the layer has 58, the base side 6 x 8; conforming, every
// element valid (the worst, .17, are padding trapezoids under the 2D
// transitions of the first two sub-layers).
TEST(ControlResolution, TemplateIsConformingAndValid) {
  const HexMesh padded = padded_tube(3);
  const ResolutionPlan plan = control_resolution(padded, {Cone{1, 0, 5.0, true}});
  ASSERT_TRUE(plan.solved);
  ASSERT_EQ(plan.layers.size(), 1u);
  EXPECT_EQ(plan.splits[0], 0);  // tip side
  EXPECT_EQ(plan.splits[2], 1);  // base side
  const HexMesh m = refine_all(padded, plan, 0);
  EXPECT_EQ(m.hexes.size(), 6u + 58u + 6u * 8u);
  EXPECT_EQ(m.hexes.size(), planned_num_hexes(plan, 0));
  EXPECT_GT(min_sj(m), 0.1);
}

// The same cone with the tip split once: the 2x2 -> 4x4 cone (the template
// followed by one regular split), conforming at each level and valid.
TEST(ControlResolution, TwoByTwoToFourByFourIsConformingAndValid) {
  const HexMesh padded = padded_tube(3);
  const ResolutionPlan plan = control_resolution(padded, {Cone{1, 0, 5.0, false}});  // tip up this time
  ASSERT_TRUE(plan.solved);
  EXPECT_EQ(plan.splits[0], 1);
  EXPECT_EQ(plan.splits[2], 0);
  const HexMesh m = refine_all(padded, plan, 1);
  EXPECT_EQ(m.hexes.size(), 6u * 64u + 58u * 8u + 6u * 8u);
  EXPECT_GT(min_sj(m), 0.1);
}

// Without cones the refinement is the regular split of everything.
TEST(ControlResolution, WithoutConesEveryLevelIsTheRegularSplit) {
  const HexMesh padded = padded_tube(2);
  const ResolutionPlan plan = control_resolution(padded, {});
  EXPECT_TRUE(std::all_of(plan.splits.begin(), plan.splits.end(), [](int x) { return x == 0; }));
  const HexMesh m = refine_all(padded, plan, 2);
  const HexMesh regular = subdivide_hex_mesh(subdivide_hex_mesh(padded));
  EXPECT_EQ(m.hexes, regular.hexes);
  EXPECT_EQ(m.vertices, regular.vertices);
}

// The finest level keeping the layers on the ideal padded tube (6 layers):
// its 6 layer sheets (5 hexahedra each, all with a valence-3 edge of the
// core's corners along the sheet) are left whole, so the 30 hexahedra of the
// layers split in 4 (across the tube only) and the 2 end caps in 8: 136
// instead of 256, conforming, the elements as good as the regular split's;
// the count that chooses the levels is the same. The chords (8 of their 20
// hexahedra have such an edge along them, at the ends) and the pillow split.
TEST(ControlResolution, FinestLevelKeepingTheLayersSplitsAcrossTheTubeOnly) {
  const HexMesh padded = padded_tube(6);
  const ResolutionPlan plan = control_resolution(padded, {});
  int levels = 0;
  RefinementSchedule s = schedule_refinement(plan, 1, levels);
  ASSERT_EQ(levels, 1);
  std::size_t kept = 0;
  const auto axes = layer_keeping_axes(padded, s, 1, 0.5, &kept);
  EXPECT_EQ(kept, 6u);
  const HexMesh m = refine_hex_mesh(padded, s, 1, &axes);
  EXPECT_EQ(m.hexes.size(), 30u * 4u + 2u * 8u);
  EXPECT_EQ(num_hexes_keeping_layers(padded, plan, 1, 0.5), m.hexes.size());
  EXPECT_TRUE(check_hex_mesh(m).valid());
  EXPECT_NEAR(min_sj(m), min_sj(subdivide_hex_mesh(padded)), 1e-12);
  // two levels: the first splits everything (12 layers of 20 hexahedra, 12 of
  // them at the core's corners), the second keeps them
  EXPECT_EQ(num_hexes_keeping_layers(padded, plan, 2, 0.5), 240u * 4u + 16u * 8u);
  // with a share over 1 nothing is kept: the regular split
  EXPECT_EQ(num_hexes_keeping_layers(padded, plan, 1, 1.5), 256u);
}

// With a cone, the sheets of the template layer and of the hexahedra not
// due at the finest level are never left whole (the level stays conforming).
TEST(ControlResolution, FinestLevelKeepingTheLayersLeavesConesAlone) {
  const HexMesh padded = padded_tube(3);
  const ResolutionPlan plan = control_resolution(padded, {Cone{1, 0, 5.0, false}});  // tip up: base at 0
  ASSERT_TRUE(plan.solved);
  int levels = 0;
  RefinementSchedule s = schedule_refinement(plan, 1, levels);
  HexMesh m = padded;
  for (int level = 1; level <= levels; ++level) {
    std::size_t kept = 0;
    const auto axes = layer_keeping_axes(m, s, level, 0.5, &kept);
    m = refine_hex_mesh(m, s, level, level == levels ? &axes : nullptr);
    EXPECT_TRUE(check_hex_mesh(m).valid()) << "level " << level;
    if (level == levels) {
      EXPECT_GT(kept, 0u);
    }
  }
  EXPECT_EQ(num_hexes_keeping_layers(padded, plan, 1, 0.5), m.hexes.size());
  EXPECT_LT(m.hexes.size(), planned_num_hexes(plan, 1));
  EXPECT_GT(min_sj(m), 0.1);
}

//! A straight skeleton along x from -h to h whose radius goes linearly from
//! r0 to r1, densely sampled.
Skeleton tapered_line(double h, double r0, double r1, int n = 61) {
  Skeleton s;
  for (int i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / (n - 1);
    s.add_node(Vec3(-h + 2 * h * t, 0, 0), r0 + (r1 - r0) * t);
  }
  for (int i = 0; i + 1 < n; ++i) s.add_edge(i, i + 1);
  return s;
}

//! The tubular structure of a skeleton after D.4 resampling.
TubularStructure structure_of(const Skeleton& s, Skeleton& resampled) {
  resampled = resample_skeleton(s);
  return build_tubular_structure(resampled);
}

TEST(ControlResolution, TaperedCapsuleHasAConeWithItsBaseOnTheThickSide) {
  Skeleton resampled;
  const TubularStructure t = structure_of(tapered_line(4.0, 1.0, 0.2), resampled);
  const auto cones = detect_cones(t, resampled);
  ASSERT_GE(cones.size(), 1u);
  EXPECT_LE(cones.size(), 2u);
  for (const Cone& c : cones) {
    EXPECT_GT(c.ratio, 4.0);
    EXPECT_GE(t.hex_arc[static_cast<std::size_t>(c.hex)], 0);  // a tube hexahedron
    // the base is the side towards -x (radius 1)
    const Hex& h = t.mesh.hexes[static_cast<std::size_t>(c.hex)];
    double x0 = 0, x1 = 0;
    for (int k = 0; k < 4; ++k) x0 += t.mesh.vertices[static_cast<std::size_t>(h[k])].x(), x1 += t.mesh.vertices[static_cast<std::size_t>(h[k + 4])].x();
    EXPECT_EQ(c.base_at_front, x1 < x0);
  }
}

TEST(ControlResolution, UniformCapsuleHasNoCone) {
  Skeleton resampled;
  const TubularStructure t = structure_of(tapered_line(4.0, 1.0, 1.0), resampled);
  EXPECT_TRUE(detect_cones(t, resampled).empty());
  // and the area test is what decides: a ratio of 1 is not > 1
  EXPECT_TRUE(detect_cones(t, resampled, {.cone_ratio = 1.01}).empty());
}

// A Y junction whose arm at 90 degrees tapers from 0.8 to 0.15: cones only
// on that terminal branch, at most two; in the plan, every pair of
// face-adjacent regular hexahedra splits equally and across each cone the
// base side splits once more than the tip side; the refinement is
// conforming at every level.
TEST(ControlResolution, YJunctionProgrammeHoldsItsEqualities) {
  Skeleton s;
  s.add_node(Vec3::Zero(), 0.8);
  const double pi = std::numbers::pi;
  for (int b = 0; b < 3; ++b) {
    const double a = pi / 2 + 2 * pi * b / 3;
    int prev = 0;
    for (int i = 1; i <= 40; ++i) {
      const double t = i / 40.0;
      const int v = s.add_node(6.0 * t * Vec3(std::cos(a), std::sin(a), 0), b == 0 ? 0.8 - 0.65 * t : 0.8);
      s.add_edge(prev, v);
      prev = v;
    }
  }
  Skeleton resampled;
  const TubularStructure t = structure_of(s, resampled);
  const auto cones = detect_cones(t, resampled);
  ASSERT_GE(cones.size(), 1u);
  EXPECT_LE(cones.size(), 2u);
  for (const Cone& c : cones) EXPECT_EQ(c.arc, cones[0].arc);
  // pad it: the outer copies 1.5 x as far from their centre
  HexMesh padded = t.mesh;
  const std::size_t core = padded.vertices.size();
  const std::vector<int> outer = pillow_hex_mesh(padded);
  for (std::size_t v = 0; v < core; ++v)
    if (outer[v] >= 0) {
      const Vec3& c = t.vertex_anchor[v];
      padded.vertices[static_cast<std::size_t>(outer[v])] = c + 1.5 * (padded.vertices[v] - c);
    }
  const ResolutionPlan plan = control_resolution(padded, cones);
  ASSERT_TRUE(plan.solved);
  EXPECT_EQ(plan.layers.size(), cones.size());
  EXPECT_EQ(plan.num_variables, padded.hexes.size() - 5 * cones.size());
  EXPECT_EQ(*std::min_element(plan.splits.begin(), plan.splits.end()), 0);
  std::map<std::array<int, 4>, std::vector<int>> faces;
  for (std::size_t h = 0; h < padded.hexes.size(); ++h)
    for (int f = 0; f < 6; ++f) {
      Quad q = hex_face(padded.hexes[h], f);
      std::sort(q.begin(), q.end());
      faces[q].push_back(static_cast<int>(h));
    }
  std::size_t equal = 0, steps = 0;
  for (const auto& [q, hs] : faces) {
    if (hs.size() != 2) continue;
    const auto a = static_cast<std::size_t>(hs[0]), b = static_cast<std::size_t>(hs[1]);
    const int la = plan.layer_of[a], lb = plan.layer_of[b];
    if (la < 0 && lb < 0) {
      EXPECT_EQ(plan.splits[a], plan.splits[b]);
      ++equal;
    } else if ((la < 0) != (lb < 0)) {  // a cone layer's tip or base
      const std::size_t regular = la < 0 ? a : b, layer = la < 0 ? b : a;
      const auto& L = plan.layers[static_cast<std::size_t>(la < 0 ? lb : la)];
      const bool on_base = std::all_of(q.begin(), q.end(), [&](int v) {
        return std::count(L.base.begin(), L.base.end(), v) + std::count(L.outer_base.begin(), L.outer_base.end(), v) > 0;
      });
      EXPECT_EQ(plan.splits[regular], plan.splits[layer] + (on_base ? 1 : 0));
      ++steps;
    }
  }
  EXPECT_GT(equal, 50u);
  EXPECT_EQ(steps, 10u * cones.size());  // 5 hexahedra, tip and base each
  refine_all(padded, plan, 1);
}

}  // namespace
}  // namespace subfab
