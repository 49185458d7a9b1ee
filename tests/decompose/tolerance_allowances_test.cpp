// SPDX-License-Identifier: GPL-3.0-or-later
// Decomposition within a tolerance by allowances (issue 17, point 2):
// tolerance_allowances() on the grooved box, and decompose() end to end.
#include "subfab/decompose/tolerance_allowances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>

#include "subfab/core/error.h"
#include "subfab/decompose/decompose.h"
#include "subfab/decompose/export_decomposition.h"
#include "subfab/fidelity/find_infeasible_features.h"
#include "subfab/mesh/read_mesh.h"
#include "subfab/validate/validate_decomposition.h"
#include "support/block_test_shapes.h"
#include "support/groove_shapes.h"
#include "support/test_shapes.h"
#include "support/test_support.h"

namespace subfab {
namespace {

using test::grooved_box_cells;
using test::voxel_mesh;

//! validate's report on the exported blocks of `r`, at its tolerance.
ValidationReport validated(const Mesh& input, const DecomposeResult& r) {
  ValidationOptions vo;
  vo.tolerance = r.tolerance;
  return validate_decomposition(input, test::to_validation(make_exported_blocks(input, r)), vo);
}

TEST(ToleranceAllowances, AllowsTheGroovesCeilingOnlyWhenItsUndercutIsWithinTheTolerance) {
  // The groove (z 4..6, 1 deep) has a ceiling facing -z: filling under it
  // leaves material 2 thick along z (the groove's height) on the +z side.
  const Mesh box = voxel_mesh(grooved_box_cells());
  ToleranceAllowanceOptions o;
  o.depth_fraction = 1.0;
  o.tolerance = 2.5;
  const std::vector<std::uint8_t> wide = tolerance_allowances(box, o);
  o.tolerance = 1.5;
  const std::vector<std::uint8_t> narrow = tolerance_allowances(box, o);
  std::size_t ceiling_wide = 0, ceiling_narrow = 0;
  for (std::size_t f = 0; f < box.num_faces(); ++f) {
    const Vec3 n = face_unit_normal(box, f);
    const double z = (box.vertices[static_cast<std::size_t>(box.faces[f][0])].z());
    if (n.z() < -0.5 && z == 6.0) {  // the groove's ceiling
      ceiling_wide += (wide[f] & 4u) ? 1 : 0;
      ceiling_narrow += (narrow[f] & 4u) ? 1 : 0;
    }
  }
  EXPECT_GT(ceiling_wide, 0u);
  EXPECT_EQ(ceiling_narrow, 0u);
  EXPECT_THROW(tolerance_allowances(box, ToleranceAllowanceOptions{}), InvalidArgumentError);
}

TEST(ToleranceAllowances, DecomposeWithinTheToleranceMakesFewerExactBlocksThatValidate) {
  const Mesh box = voxel_mesh(grooved_box_cells());
  DecomposeOptions exact;
  exact.orient = false;
  const DecomposeResult e = decompose(box, exact);
  DecomposeOptions within = exact;
  within.tolerance_abs = 2.5;
  within.tolerance_fraction = 1.0;
  const DecomposeResult t = decompose(box, within);
  EXPECT_LT(t.blocks.size(), e.blocks.size());
  EXPECT_GT(t.num_allowed_faces, 0u);
  EXPECT_LE(t.deviation_bound, 2.5);
  for (const Block& b : t.blocks) {
    EXPECT_TRUE(check_closed_solid(b.mesh).ok());
    EXPECT_TRUE(is_height_field(b.mesh, axis_direction(b.axis)));  // exact: the milled shape is the block
  }
}


TEST(ToleranceAllowances, UndercutDepthsGiveTheAllowancesOfEveryLevel) {
  // Under the groove's ceiling (z = 6, facing -z) the free column runs down
  // to the groove's floor (z = 4): depth 2 along z, and none along x or y.
  const Mesh box = voxel_mesh(grooved_box_cells());
  ToleranceAllowanceOptions o;
  o.tolerance = 1.2;
  o.depth_fraction = 2.0;
  const auto depths = undercut_depths(box, o);
  ASSERT_EQ(depths.size(), box.num_faces());
  const std::vector<double> fractions{2.0, 1.0, 0.5};
  std::vector<std::array<std::uint8_t, 3>> level(box.num_faces(), {0, 0, 0});
  std::size_t ceiling = 0;
  for (std::size_t f = 0; f < box.num_faces(); ++f) {
    const Vec3 n = face_unit_normal(box, f);
    const double z = box.vertices[static_cast<std::size_t>(box.faces[f][0])].z();
    if (n.z() < -0.5 && z == 6.0) {
      ++ceiling;
      EXPECT_NEAR(depths[f][2], 2.0, 1e-9);
      EXPECT_TRUE(std::isinf(depths[f][0]) && std::isinf(depths[f][1]));
    }
  }
  ASSERT_GT(ceiling, 0u);
  // Level 0 (2 x 1.2 = 2.4 >= 2): every ceiling face allowed along z.
  auto count_z = [&](const std::vector<std::uint8_t>& a) {  // ceiling faces allowed along z
    std::size_t c = 0;
    for (std::size_t f = 0; f < a.size(); ++f)
      c += (face_unit_normal(box, f).z() < -0.5 && box.vertices[static_cast<std::size_t>(box.faces[f][0])].z() == 6.0 &&
            (a[f] & 4u))
               ? 1
               : 0;
    return c;
  };
  EXPECT_EQ(count_z(allowances_at(depths, level, fractions, o.tolerance)), ceiling);
  // Level 1 (1 x 1.2 < 2): none; past the last level: none either.
  for (auto& l : level) l[2] = 1;
  EXPECT_EQ(count_z(allowances_at(depths, level, fractions, o.tolerance)), 0u);
  for (auto& l : level) l = {3, 3, 3};
  EXPECT_EQ(count_allowed_faces(allowances_at(depths, level, fractions, o.tolerance)), 0u);
  EXPECT_THROW(allowances_at(depths, {}, fractions, o.tolerance), InvalidArgumentError);
}

TEST(ToleranceAllowances, AnUndercutDeeperThanHalfTheToleranceIsAllowedAndMeasured) {
  // T = 1.2: the groove's fill deviates 1 <= T, its undercut depth is 2.
  // At the first depth fraction (2) the ceiling is allowed, one block; at
  // 0.5 alone it is not (2 > 0.6).
  const Mesh box = voxel_mesh(grooved_box_cells());
  DecomposeOptions within;
  within.orient = false;
  within.tolerance_abs = 1.2;
  within.tolerance_fraction = 1.0;
  const DecomposeResult t = decompose(box, within);
  EXPECT_GT(t.num_allowed_faces, 0u);
  EXPECT_EQ(t.blocks.size(), 1u);
  EXPECT_LE(t.deviation_bound, 1.2);
  for (const Block& b : t.blocks) EXPECT_TRUE(is_height_field(b.mesh, axis_direction(b.axis)));
  within.tolerance_depth_fractions = {0.5};  // the faces of zero depth (the base's) only
  EXPECT_LT(decompose(box, within).num_allowed_faces, t.num_allowed_faces);
  within.tolerance_depth_fractions = {};
  EXPECT_THROW(decompose(box, within), InvalidArgumentError);
}

TEST(ToleranceAllowances, AnAllowanceTheMeasureRefutesIsLoweredAndTheResultStaysExact) {
  // T = 0.9 < the groove's depth 1: allowed at fraction 4 (2 <= 3.6), the
  // milled shape then deviates 1 > T and fails; the next level (0.5 x 0.9)
  // allows nothing there, and no merge within 0.9 exists: the exact blocks.
  const Mesh box = voxel_mesh(grooved_box_cells());
  DecomposeOptions within;
  within.orient = false;
  const std::size_t exact = decompose(box, within).blocks.size();
  within.tolerance_abs = 0.9;
  within.tolerance_fraction = 1.0;
  within.tolerance_depth_fractions = {4.0, 0.5};
  const DecomposeResult t = decompose(box, within);
  EXPECT_GT(t.num_allowed_faces, 0u);
  EXPECT_GE(t.num_tolerance_rounds, 1);
  EXPECT_EQ(t.blocks.size(), exact);
  EXPECT_LE(t.deviation_bound, 0.9);
  for (const Block& b : t.blocks) EXPECT_TRUE(is_height_field(b.mesh, axis_direction(b.axis)));
}


//! Two 10 x 10 x 10 boxes with a groove round their four sides at z in
//! [4, 6], 1 deep in the first (x in [0, 10]) and 2 deep in the second (x in
//! [14, 24]), joined by a bar (x in [10, 14], y in [4, 6], z in [0, 1]).
//! In a 13 x 13 x 13 work volume no block holds both boxes.
std::set<test::Cell> two_grooved_boxes_cells() {
  std::set<test::Cell> cells;
  for (int b = 0; b < 2; ++b) {
    const int x0 = 14 * b, depth = 1 + b;
    for (const auto& c : test::cells_of_box({x0, 0, 0}, {x0 + 10, 10, 10})) {
      const int x = c[0] - x0;
      const bool groove = (c[2] == 4 || c[2] == 5) &&
                          (x < depth || x >= 10 - depth || c[1] < depth || c[1] >= 10 - depth);
      if (!groove) cells.insert(c);
    }
  }
  for (const auto& c : test::cells_of_box({10, 4, 0}, {14, 6, 1})) cells.insert(c);
  return cells;
}

TEST(ToleranceAllowances, BlocksStillBeyondTheToleranceAfterTheLastRoundAreDecomposedAgainInPlace) {
  // T = 1.5, one round, both grooves' ceilings allowed (fraction 4): the
  // first box's milled shape deviates 1 <= T and is kept (one block), the
  // second's deviates 2 > T and no round is left. Only that block's carved
  // piece is replaced by its exact blocks, every block an exact height
  // field, the deviation within T; decomposing the whole model again
  // instead (tolerance_local_exact = false: the exact path, then the merges
  // within T) gives no fewer blocks.
  const Mesh boxes = voxel_mesh(two_grooved_boxes_cells());
  DecomposeOptions within;
  within.orient = false;
  within.machine = Vec3(13, 13, 13);
  within.tolerance_abs = 1.5;
  within.tolerance_fraction = 1.0;
  within.tolerance_depth_fractions = {4.0};
  within.tolerance_rounds = 1;
  within.tolerance_floor_scale = 0;
  const DecomposeResult t = decompose(boxes, within);
  EXPECT_EQ(t.num_tolerance_rounds, 1);
  EXPECT_EQ(t.num_blocks_decomposed_in_place, 1u);
  EXPECT_LE(t.deviation_bound, 1.5);
  ASSERT_EQ(t.filled.size(), t.blocks.size());
  EXPECT_EQ(std::count(t.filled.begin(), t.filled.end(), char{1}), 1);  // the first box, its groove filled
  for (const Block& b : t.blocks) {
    EXPECT_TRUE(check_closed_solid(b.mesh).ok());
    EXPECT_TRUE(is_height_field(b.mesh, axis_direction(b.axis)));
  }
  within.tolerance_local_exact = false;
  const DecomposeResult g = decompose(boxes, within);
  EXPECT_EQ(g.num_blocks_decomposed_in_place, 0u);
  EXPECT_LE(t.blocks.size(), g.blocks.size());  // 4 and 4: the merges within T make the first box one block there
}

//! A 10 x 10 plate (z in [0, 1]), a 4 x 4 core (z in [1, 8]) and a 10 x 10
//! slab (z in [8, 12]) whose rim hangs 1 lower (a lip: the outer ring of
//! cells at z in [7, 8]) and a knob on top (z in [12, 13]: no block holds the
//! slab along -z). Under the slab, between the lip and the core, the ceiling
//! (z = 8, facing -z) has a free column 7 deep down to the plate: its
//! undercut depth is 7. Exactly: the slab with the knob (+z, base 8), the lip
//! and the plate with the core: 3 blocks.
std::set<test::Cell> lipped_slab_cells() {
  std::set<test::Cell> cells = test::cells_of_box({0, 0, 0}, {10, 10, 1});
  for (const auto& c : test::cells_of_box({3, 3, 1}, {7, 7, 8})) cells.insert(c);
  for (const auto& c : test::cells_of_box({0, 0, 8}, {10, 10, 12})) cells.insert(c);
  for (const auto& c : test::cells_of_box({0, 0, 7}, {10, 10, 8}))
    if (c[0] == 0 || c[0] == 9 || c[1] == 0 || c[1] == 9) cells.insert(c);
  for (const auto& c : test::cells_of_box({4, 4, 12}, {6, 6, 13})) cells.insert(c);  // no block along -z
  return cells;
}

TEST(ToleranceAllowances, ABaseFloorLetsABlockWhoseBaseLiesJustUnderAShallowOverhangHoldIt) {
  // A +z block with its base at the lip's bottom (z = 7) fills the ring
  // under the ceiling 1 deep: its milled shape deviates 1 from the input.
  // Per face (undercut depth 7 > 2 T) the ceiling may never lean; with base
  // floors (8 - q T / 1 <= 7) it may in that block: the slab, the lip and
  // the top of the core become one block, 2 in all, within T = 1.2. Below
  // the deviation (T = 0.8) the measure refutes that and the blocks stay
  // exact.
  const Mesh solid = voxel_mesh(lipped_slab_cells());
  DecomposeOptions o;
  o.orient = false;
  const std::size_t exact = decompose(solid, o).blocks.size();
  EXPECT_EQ(exact, 3u);
  o.tolerance_fraction = 1.0;
  o.tolerance_abs = 1.2;
  o.tolerance_floor_scale = 1.0;
  const DecomposeResult floored = decompose(solid, o);
  EXPECT_EQ(floored.blocks.size(), 2u);
  EXPECT_GT(floored.num_floored_faces, 0u);
  EXPECT_GT(floored.deviation_bound, 0.9);  // the filled ring, 1 deep
  EXPECT_LE(floored.deviation_bound, 1.2);
  for (const Block& b : floored.blocks) EXPECT_TRUE(is_height_field(b.mesh, axis_direction(b.axis)));
  const ValidationReport report = validated(solid, floored);
  for (const CheckReport& c : report.checks) {
    // T is 6.5% of this small model's diagonal: the plate (1 thick, 5.4%) is
    // thinner than T by construction, so the sliver check is not asked here.
    if (c.name.rfind("no slivers", 0) == 0) continue;
    EXPECT_TRUE(c.passed) << c.name << ": " << (c.failures.empty() ? c.summary : c.failures[0]);
  }
  // Per face the ceiling may not lean (undercut 7 > 2 T); with floors it may
  // above z = 8 - 2 T = 5.6. (Per face this shape also ends with 2 blocks, by
  // another cover: the count alone does not tell the two apart here.)
  ToleranceAllowanceOptions ao;
  ao.tolerance = 1.2;
  ao.depth_fraction = 2.0;
  const auto depths = undercut_depths(solid, ao);
  const std::vector<std::array<std::uint8_t, 3>> level0(solid.num_faces(), {0, 0, 0});
  const OverhangAllowances per_face = allowances_with_floors(solid, depths, level0, {2.0}, 1.2, 0.0);
  const OverhangAllowances with_floors = allowances_with_floors(solid, depths, level0, {2.0}, 1.2, 1.0);
  std::size_t ceiling = 0;
  for (std::size_t f = 0; f < solid.num_faces(); ++f) {
    const double z = solid.vertices[static_cast<std::size_t>(solid.faces[f][0])].z();
    if (face_unit_normal(solid, f).z() > -0.5 || z != 8.0) continue;
    ++ceiling;
    EXPECT_FALSE(per_face.bits[f] & 4u);
    EXPECT_TRUE(with_floors.bits[f] & 4u);
    EXPECT_DOUBLE_EQ(with_floors.floors[f][2], 8.0 - 2.4);
  }
  EXPECT_GT(ceiling, 0u);
  EXPECT_EQ(count_floored_faces(per_face), 0u);
  o.tolerance_abs = 0.8;
  const DecomposeResult below = decompose(solid, o);
  EXPECT_EQ(below.blocks.size(), exact);
  EXPECT_LE(below.deviation_bound, 0.8);
}


// Regression (num_allowed_faces said 53 of 10796 faces on airplane at the
// default floors, 3882 per face): a face allowed in every box along one
// axis and only above a floor along another is allowed everywhere, not
// floored. count_changed_faces() also counts a floor that rises.
TEST(ToleranceAllowances, AFaceAllowedEverywhereOnOneAxisIsNotCountedAsFloored) {
  const double inf = std::numeric_limits<double>::infinity();
  OverhangAllowances a;
  a.bits = {0b001 | 0b100, 0b100, 0b010, 0};
  a.floors = {{-inf, 0, 3.0}, {0, 0, 2.0}, {0, -inf, 0}, {1.0, 1.0, 1.0}};
  EXPECT_EQ(count_floored_faces(a), 1u);  // face 1 only
  EXPECT_EQ(count_changed_faces(a, a), 0u);
  OverhangAllowances b = a;
  b.floors[1][2] = 2.5;  // a floor rises: bit kept, allowance smaller
  b.floors[3][0] = 7.0;  // unused floor (bit clear): no change
  b.bits[2] = 0;         // a bit cleared
  EXPECT_EQ(count_changed_faces(a, b), 2u);
}

// Regression (issue 17, "every closed model gets blocks at the default"): a
// spike 3.3e-4 x the diagonal tall that no axis sees. The thin-feature
// repair fails on it (its smoothing makes the surface cross itself), so the
// exact path exits 3; within a tolerance of 5e-4 its faces may lean past
// vertical, so it is left to the tolerance: no repair, exact blocks that
// validate within the tolerance.
TEST(ToleranceAllowances, ASpikeTheRepairCannotFixIsLeftToTheTolerance) {
  const Mesh spiked = read_mesh(test::data_path("regression/cube_tiny_diagonal_spike.obj"));
  ASSERT_FALSE(find_infeasible_features(spiked).feasible());
  DecomposeOptions o;
  try {
    decompose(spiked, o);
    ADD_FAILURE() << "the exact path decomposed the spike: the regression mesh no longer reproduces the failure";
  } catch (const AlgorithmError& e) {
    EXPECT_NE(std::string(e.what()).find("the local repair of infeasible features failed"), std::string::npos)
        << e.what();
  }
  o.tolerance_fraction = 5e-4;
  const DecomposeResult t = decompose(spiked, o);
  EXPECT_EQ(t.num_features_within_tolerance, 1u);
  EXPECT_FALSE(t.repaired_input.has_value());
  EXPECT_EQ(t.repair.num_features, 0);
  ASSERT_FALSE(t.blocks.empty());
  for (const Block& b : t.blocks) {
    EXPECT_TRUE(check_closed_solid(b.mesh).ok());
    EXPECT_TRUE(is_height_field(b.mesh, axis_direction(b.axis)));  // exact whatever the tolerance
  }
  const ValidationReport report = validated(spiked, t);
  for (const CheckReport& c : report.checks)
    EXPECT_TRUE(c.passed) << c.name << ": " << (c.failures.empty() ? c.summary : c.failures[0]);
  // --exact refuses to repair, but nothing needs repairing within the tolerance.
  o.repair = false;
  EXPECT_EQ(decompose(spiked, o).blocks.size(), t.blocks.size());
  // Below the spike's undercut (its depth > 2 x T) the features are not
  // covered, the repair runs and fails as at T = 0.
  o.repair = true;
  o.tolerance_fraction = 1e-6;
  EXPECT_THROW(decompose(spiked, o), AlgorithmError);
}


// When the blocks holding a feature left to the tolerance fail the measure
// even with only the feature's allowances, the feature is repaired after all
// (the fallback) and the stages run on the repaired solid. The regression
// spike made 50 times larger (the repair handles that one) under a depth
// fraction so large that its faces are allowed while their fill deviates
// more than T.
TEST(ToleranceAllowances, AFeatureWhoseBlocksFailTheMeasureIsRepairedAfterAll) {
  Mesh spiked = read_mesh(test::data_path("regression/cube_tiny_diagonal_spike.obj"));
  for (std::size_t v = 8; v < spiked.num_vertices(); ++v)  // the spike's vertices, about the top face's centre
    spiked.vertices[v] = Vec3(0.5, 0.5, 1) + 50 * (spiked.vertices[v] - Vec3(0.5, 0.5, 1));
  DecomposeOptions o;
  o.tolerance_fraction = 1e-3;
  o.tolerance_rounds = 1;
  o.tolerance_depth_fractions = {100.0};
  o.tolerance_floor_scale = 0;  // per face: one allowances' round, then the pinned one (floors would add rounds)
  const DecomposeResult t = decompose(spiked, o);
  EXPECT_EQ(t.num_features_within_tolerance, 0u);
  EXPECT_TRUE(t.repaired_input.has_value());
  EXPECT_GT(t.repair.num_features, 0);
  EXPECT_GE(t.num_tolerance_rounds, 2);  // the allowances' round and the pinned one failed
  for (const Block& b : t.blocks) {
    EXPECT_TRUE(check_closed_solid(b.mesh).ok());
    EXPECT_TRUE(is_height_field(b.mesh, axis_direction(b.axis)));
  }
  EXPECT_LE(t.deviation_bound, t.tolerance);
}

// The exact decomposition is made first; a round under allowances that
// carves far more blocks (moai at the thesis's 3.8e-4 and height 0.225: 9
// against 7 exact) is given up before its measure, the exact blocks kept:
// the same blocks as when the round is measured and loses, without the
// measure (tolerance_exact_margin < 0: never given up).
TEST(ToleranceAllowances, ARoundCarvingFarMoreBlocksThanTheExactOnesIsNotMeasured) {
  const Mesh moai = read_mesh(test::data_path("moai.obj"));
  DecomposeOptions o;
  o.tolerance_fraction = 3.8e-4;
  o.max_height_fraction = 0.225;
  o.tolerance_overhang_ladder_deg.clear();  // the exact blocks as the round left them (the ladder: below)
  const DecomposeResult given_up = decompose(moai, o);
  EXPECT_EQ(given_up.num_tolerance_rounds, 0);
  DecomposeOptions measured = o;
  measured.tolerance_exact_margin = -1;
  const DecomposeResult m = decompose(moai, measured);
  EXPECT_GE(m.num_tolerance_rounds, 1);
  ASSERT_EQ(given_up.blocks.size(), m.blocks.size());
  for (std::size_t i = 0; i < m.blocks.size(); ++i) {
    EXPECT_EQ(given_up.blocks[i].axis, m.blocks[i].axis);
    EXPECT_EQ(given_up.blocks[i].mesh.vertices, m.blocks[i].mesh.vertices);
  }
  EXPECT_EQ(given_up.deviation_bound, 0.0);
  DecomposeOptions bad = o;
  bad.tolerance_exact_margin = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(decompose(moai, bad), InvalidArgumentError);
}

// A 10 x 10 x 10 box with a stem on top, 2 x 2 at z = 10 and flaring to
// 2 + 2w at z = 13 (w = 3 tan 8 deg): the stem's four sides lean 8 deg past
// vertical for +z, over a drop of 3 to the box's top.
Mesh box_with_flared_stem() {
  const double w = 3 * std::tan(8.0 * std::acos(-1.0) / 180.0);
  Mesh m;
  m.vertices = {{0, 0, 0},          {10, 0, 0},         {10, 10, 0},        {0, 10, 0},         {0, 0, 10},
                {10, 0, 10},        {10, 10, 10},       {0, 10, 10},        {4, 4, 10},         {6, 4, 10},
                {6, 6, 10},         {4, 6, 10},         {4 - w, 4 - w, 13}, {6 + w, 4 - w, 13}, {6 + w, 6 + w, 13},
                {4 - w, 6 + w, 13}};
  m.faces = {{0, 2, 1},   {0, 3, 2},   {0, 1, 5},   {0, 5, 4},   {1, 2, 6},    {1, 6, 5},    {2, 3, 7},
             {2, 7, 6},   {3, 0, 4},   {3, 4, 7},   {4, 5, 9},   {4, 9, 8},    {5, 6, 10},   {5, 10, 9},
             {6, 7, 11},  {6, 11, 10}, {7, 4, 8},   {7, 8, 11},  {8, 9, 13},   {8, 13, 12},  {9, 10, 14},
             {9, 14, 13}, {10, 11, 15}, {10, 15, 14}, {11, 8, 12}, {11, 12, 15}, {12, 13, 14}, {12, 14, 15}};
  return m;
}

TEST(ToleranceAllowances, AUniformAngleAllowsTheFacesLeaningAtMostThatFarOnTheirAxisOnly) {
  const Mesh m = box_with_flared_stem();
  ASSERT_TRUE(check_closed_solid(m).ok());
  const OverhangAllowances at5 = uniform_overhang_allowances(m, 5.0);
  const OverhangAllowances at10 = uniform_overhang_allowances(m, 10.0);
  const OverhangAllowances at45 = uniform_overhang_allowances(m, 45.0);
  EXPECT_EQ(count_allowed_faces(at5.bits), 0u);
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const bool stem_side = f >= 18 && f < 26;
    EXPECT_EQ(at10.bits[f], stem_side ? 4u : 0u) << "face " << f;  // z only: the sides face +x/-x, +y/-y
    EXPECT_EQ(at45.bits[f], at10.bits[f]) << "face " << f;  // the box's bottom (n.z = -1) leans 90 deg
    for (double floor : at10.floors[f]) EXPECT_EQ(floor, -std::numeric_limits<double>::infinity());
  }
  EXPECT_EQ(count_allowed_faces(uniform_overhang_allowances(m, 0.0).bits), 0u);
}

// The overhang ladder (issue 17): with the depth allowances made useless
// (depth fraction 1e-3, no floors) the round leaves the exact blocks; at 10
// deg (5 deg allows no face) the box and its stem are one +z block whose
// milled shape fills the wedges under the stem's sides (about 0.37 from the
// input). Kept within T = 1; at T = 0.3 the measure refutes it (and the
// merge of the exact blocks) and the exact blocks stay.
TEST(ToleranceAllowances, TheOverhangLadderKeepsAUniformAngleWhoseMilledShapesPass) {
  const Mesh m = box_with_flared_stem();
  DecomposeOptions o;
  o.orient = false;
  const std::size_t exact = decompose(m, o).blocks.size();
  EXPECT_GE(exact, 2u);
  o.tolerance_fraction = 1.0;
  o.tolerance_abs = 1.0;
  o.tolerance_depth_fractions = {1e-3};
  o.tolerance_floor_scale = 0.0;
  // Without the ladder only the merge of the exact blocks (stage 8) makes
  // the one +z block; with it the ladder's carve is that block already.
  DecomposeOptions no_ladder = o;
  no_ladder.tolerance_overhang_ladder_deg.clear();
  const DecomposeResult merged = decompose(m, no_ladder);
  EXPECT_EQ(merged.tolerance_overhang_deg, 0.0);
  EXPECT_GE(merged.num_tolerance_merges, 1u);
  const DecomposeResult laddered = decompose(m, o);
  ASSERT_EQ(laddered.blocks.size(), 1u);
  EXPECT_EQ(laddered.tolerance_overhang_deg, 10.0);
  EXPECT_EQ(laddered.num_tolerance_merges, 0u);
  EXPECT_EQ(laddered.blocks[0].axis, Axis::PosZ);
  EXPECT_GT(laddered.deviation_bound, 0.2);
  EXPECT_LE(laddered.deviation_bound, 1.0);
  EXPECT_TRUE(is_height_field(laddered.blocks[0].mesh, axis_direction(laddered.blocks[0].axis)));
  const ValidationReport report = validated(m, laddered);
  for (const CheckReport& c : report.checks)
    EXPECT_TRUE(c.passed) << c.name << ": " << (c.failures.empty() ? c.summary : c.failures[0]);
  o.tolerance_abs = 0.3;
  const DecomposeResult refuted = decompose(m, o);
  EXPECT_EQ(refuted.blocks.size(), exact);
  EXPECT_EQ(refuted.tolerance_overhang_deg, 0.0);
  DecomposeOptions bad = o;
  bad.tolerance_overhang_ladder_deg = {10, 5};
  EXPECT_THROW(decompose(m, bad), InvalidArgumentError);
  bad.tolerance_overhang_ladder_deg = {50};
  EXPECT_THROW(decompose(m, bad), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
