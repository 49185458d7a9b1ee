// SPDX-License-Identifier: GPL-3.0-or-later
// The blocking relation and the gluing order on small shapes whose answer
// is known by hand.
#include "subfab/view/plan_gluing_order.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "decomposition_folder.h"
#include "subfab/core/error.h"

namespace subfab {
namespace {

using test::make_box_mesh;

constexpr int kPosX = 0, kNegX = 1, kPosY = 2, kNegY = 3, kPosZ = 4, kNegZ = 5;

std::vector<Mesh> meshes_of(const std::vector<test::FolderBlock>& blocks) {
  std::vector<Mesh> out;
  for (const auto& b : blocks) out.push_back(b.mesh);
  return out;
}

TEST(PlanGluingOrder, AxisLabelsRoundTrip) {
  for (int d = 0; d < 6; ++d) EXPECT_EQ(axis_index(axis_label(d)), d);
  EXPECT_EQ(axis_index("z"), kPosZ);
  EXPECT_EQ(axis_index("up"), -1);
}

TEST(PlanGluingOrder, StackedBoxesBlockOnlyAlongTheStack) {
  // B sits on A, sharing the face z = 1.
  const std::vector<Mesh> blocks{make_box_mesh({0, 0, 0}, {1, 1, 1}), make_box_mesh({0, 0, 1}, {1, 1, 2})};
  const BlockingRelation r = compute_blocking(blocks);
  EXPECT_TRUE(r(kPosZ, 0, 1));   // A cannot leave upwards through B
  EXPECT_TRUE(r(kNegZ, 1, 0));   // B cannot leave downwards through A
  EXPECT_FALSE(r(kNegZ, 0, 1));
  EXPECT_FALSE(r(kPosZ, 1, 0));
  for (int d : {kPosX, kNegX, kPosY, kNegY}) {
    EXPECT_FALSE(r(d, 0, 1)) << axis_label(d);
    EXPECT_FALSE(r(d, 1, 0)) << axis_label(d);
  }
}

TEST(PlanGluingOrder, BoxesSideBySideDoNotBlockVertically) {
  const std::vector<Mesh> blocks{make_box_mesh({0, 0, 0}, {1, 1, 1}), make_box_mesh({1, 0, 0}, {2, 1, 1})};
  const BlockingRelation r = compute_blocking(blocks);
  EXPECT_TRUE(r(kPosX, 0, 1));
  EXPECT_TRUE(r(kNegX, 1, 0));
  for (int d : {kPosY, kNegY, kPosZ, kNegZ}) EXPECT_FALSE(r(d, 0, 1) || r(d, 1, 0)) << axis_label(d);
}

TEST(PlanGluingOrder, KeyInACupGoesInLastFromAbove) {
  const auto blocks = test::cup_and_key();
  const BlockingRelation r = compute_blocking(meshes_of(blocks));
  // The key is held on four sides and from below; only +z frees it.
  for (int d : {kPosX, kNegX, kPosY, kNegY, kNegZ}) {
    bool blocked = false;
    for (std::size_t c = 0; c < 5; ++c) blocked = blocked || r(d, 5, c);
    EXPECT_TRUE(blocked) << axis_label(d);
  }
  for (std::size_t c = 0; c < 5; ++c) EXPECT_FALSE(r(kPosZ, 5, c));

  // As the assembly sheet calls it: milling axes preferred, small blocks
  // leave first. The base (largest) is glued first; the key comes from +z
  // (it still has the base below it when it goes in).
  GluingOptions options;
  for (const auto& b : blocks) {
    options.preferred_axis.push_back(axis_index(b.axis));
    options.volumes.push_back(signed_volume(b.mesh));
  }
  const GluingPlan plan = plan_gluing_order(meshes_of(blocks), options);
  ASSERT_EQ(plan.steps.size(), 6u);
  EXPECT_TRUE(plan.stuck.empty());
  EXPECT_EQ(plan.steps.front().block, 0u);
  EXPECT_EQ(plan.steps.front().axis, -1);
  std::size_t key_step = 0;
  while (plan.steps[key_step].block != 5) ++key_step;
  EXPECT_EQ(plan.steps[key_step].axis, kPosZ);
  // Every block appears once, and every step's block is free along its
  // axis from the blocks glued before it.
  std::vector<int> seen(6, 0);
  for (std::size_t s = 0; s < plan.steps.size(); ++s) {
    ++seen[plan.steps[s].block];
    if (plan.steps[s].axis < 0) continue;
    for (std::size_t t = 0; t < s; ++t) EXPECT_FALSE(r(plan.steps[s].axis, plan.steps[s].block, plan.steps[t].block));
  }
  EXPECT_EQ(seen, std::vector<int>(6, 1));
}

TEST(PlanGluingOrder, DumbbellThroughARingIsStuck) {
  // A square ring around the z axis and a dumbbell whose bar passes through
  // it, with caps wider than the hole on both sides: no straight move frees either.
  const Mesh ring = test::union_of_boxes({{{0, 0, 0}, {3, 1, 1}},
                                          {{0, 2, 0}, {3, 3, 1}},
                                          {{0, 1, 0}, {1, 2, 1}},
                                          {{2, 1, 0}, {3, 2, 1}}});
  const Mesh dumbbell = test::union_of_boxes({{{1, 1, 0}, {2, 2, 1}},
                                              {{1, 1, 1}, {2, 2, 2}},
                                              {{0.5, 0.5, 2}, {2.5, 2.5, 2.5}},
                                              {{1, 1, -1}, {2, 2, 0}},
                                              {{0.5, 0.5, -1.5}, {2.5, 2.5, -1}}});
  const GluingPlan plan = plan_gluing_order({ring, dumbbell});
  EXPECT_EQ(plan.stuck.size(), 2u);
  ASSERT_EQ(plan.steps.size(), 2u);
  EXPECT_EQ(plan.steps[0].axis, -1);
  // With a third, free block on top, that one still gets a step of its own.
  const GluingPlan three = plan_gluing_order({ring, dumbbell, make_box_mesh({0, 0, 3}, {1, 1, 4})});
  EXPECT_EQ(three.stuck.size(), 2u);
  ASSERT_EQ(three.steps.size(), 3u);
  EXPECT_EQ(three.steps[2].block, 2u);
  EXPECT_GE(three.steps[2].axis, 0);
}

TEST(PlanGluingOrder, FollowsTheDecompositionFrame) {
  // The cup and key rotated out of the axes; with the rotation given, the
  // answer is the same as in the axis-aligned frame.
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<Mesh> rotated = meshes_of(test::cup_and_key());
  for (Mesh& m : rotated) transform_mesh(m, r.transpose(), Vec3::Zero());  // input = R^T * frame
  GluingOptions options;
  options.rotation = r;
  const BlockingRelation rotated_relation = compute_blocking(rotated, options);
  const BlockingRelation relation = compute_blocking(meshes_of(test::cup_and_key()));
  for (int d = 0; d < 6; ++d) EXPECT_EQ(rotated_relation.blocked[d], relation.blocked[d]) << axis_label(d);
}

TEST(PlanGluingOrder, PrefersTheMillingDirectionAndSmallBlocksFirst) {
  // Two boxes side by side in x: the smaller one leaves first (is glued
  // last), along its preferred axis when that one is free.
  const std::vector<Mesh> blocks{make_box_mesh({0, 0, 0}, {2, 1, 1}), make_box_mesh({2, 0, 0}, {3, 1, 1})};
  GluingOptions options;
  options.volumes = {2.0, 1.0};
  options.preferred_axis = {-1, kPosX};
  const GluingPlan plan = plan_gluing_order(blocks, options);
  ASSERT_EQ(plan.steps.size(), 2u);
  EXPECT_EQ(plan.steps[0].block, 0u);
  EXPECT_EQ(plan.steps[0].axis, -1);
  EXPECT_EQ(plan.steps[1].block, 1u);
  EXPECT_EQ(plan.steps[1].axis, kPosX);
}

TEST(PlanGluingOrder, RejectsABadResolution) {
  GluingOptions options;
  options.resolution = 1;
  EXPECT_THROW(plan_gluing_order({make_box_mesh({0, 0, 0}, {1, 1, 1})}, options), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
