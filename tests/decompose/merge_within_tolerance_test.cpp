// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/merge_within_tolerance.h"

#include <gtest/gtest.h>

#include "subfab/core/error.h"
#include "subfab/validate/measure_fill_deviation.h"
#include "subfab/validate/validate_decomposition.h"
#include "support/block_test_shapes.h"
#include "support/groove_shapes.h"
#include "support/test_shapes.h"

namespace subfab {
namespace {

using test::grooved_box_cells;
using test::slab_of;
using test::voxel_mesh;

//! The grooved box's two exact halves: the top along -z, the bottom along +z.
std::vector<Block> halves(const std::set<test::Cell>& cells, bool no_plug = false) {
  return {Block{voxel_mesh(slab_of(cells, 5, 10, no_plug)), Axis::NegZ, 0},
          Block{voxel_mesh(slab_of(cells, 0, 5, no_plug)), Axis::PosZ, 1}};
}

TEST(MergeWithinTolerance, AShallowUndercutWithinTheToleranceMakesOneBlock) {
  // The groove is 1 deep: at T = 1.5 (> 1 + the error bound 0.075) the two
  // halves become one block, the milled shape of their union: the full box,
  // an exact height field, 1 from the input. (The screen is opened wide so
  // that +-z, which fills the whole groove, is tried first: by default it
  // skips it, the groove being 2 high, and an x direction fills one side.)
  const Mesh solid = voxel_mesh(grooved_box_cells());
  ToleranceMergeOptions o;
  o.tolerance = 1.5;
  o.screen_factor = 10;
  const ToleranceMergeResult r = merge_within_tolerance(solid, halves(grooved_box_cells()), o);
  ASSERT_EQ(r.blocks.size(), 1u);
  EXPECT_EQ(r.num_merges, 1u);
  ASSERT_EQ(r.filled.size(), 1u);
  EXPECT_EQ(r.filled[0], 1);
  const Block& b = r.blocks[0];
  EXPECT_TRUE(check_closed_solid(b.mesh).ok());
  EXPECT_TRUE(is_height_field(b.mesh, axis_direction(b.axis)));
  EXPECT_NEAR(signed_volume(b.mesh), 1000.0, 1e-9);  // the groove (4 x 2 x 9 x 1 ... = 72) is filled
  EXPECT_GE(r.max_deviation, 1.0);
  EXPECT_LE(r.max_deviation, 1.5);
  // Measured again from scratch: within the tolerance.
  const FillDeviationMeter meter(solid);
  EXPECT_LE(meter.measure(b.mesh, {}, {.reach = 1.5, .error = 0.01}).bound(), 1.5);
}

TEST(MergeWithinTolerance, AnUndercutDeeperThanTheToleranceStaysTwoBlocks) {
  const Mesh solid = voxel_mesh(grooved_box_cells());
  ToleranceMergeOptions o;
  o.tolerance = 0.9;  // the groove is 1 deep
  const ToleranceMergeResult r = merge_within_tolerance(solid, halves(grooved_box_cells()), o);
  EXPECT_EQ(r.blocks.size(), 2u);
  o.screen_factor = 10;  // the same with every direction measured
  EXPECT_EQ(merge_within_tolerance(solid, halves(grooved_box_cells()), o).blocks.size(), 2u);
  EXPECT_EQ(r.num_merges, 0u);
  for (char f : r.filled) EXPECT_EQ(f, 0);
}

TEST(MergeWithinTolerance, AMergeWhoseFillWouldCollideWithAnotherBlockIsNotTaken) {
  // A small cube floats in the groove's +x side (a second shell of the
  // solid, its own block). Along +-z the halves' milled shape would fill the
  // groove all round, through the cube: within the tolerance, but a
  // collision, so that merge must not be taken. Along +x the milled shape
  // fills only the -x groove (1 deep) and stops short of the cube, so at
  // T = 1.5 the halves still merge, along x, and overlap nothing.
  const Mesh cube = test::box_solid({9.25, 4.5, 4.25}, {9.75, 5.5, 5.75});
  const Mesh solid = test::append(voxel_mesh(grooved_box_cells()), cube);
  std::vector<Block> blocks = halves(grooved_box_cells());
  blocks.push_back(Block{cube, Axis::PosX, 2});
  ToleranceMergeOptions o;
  o.tolerance = 1.5;
  o.screen_factor = 10;  // +-z is tried first, and must be refused for the collision
  const ToleranceMergeResult r = merge_within_tolerance(solid, blocks, o);
  ASSERT_EQ(r.blocks.size(), 2u);
  EXPECT_EQ(r.num_merges, 1u);
  for (const Block& b : r.blocks)
    if (signed_volume(b.mesh) > 500) {
      EXPECT_TRUE(b.axis == Axis::PosX || b.axis == Axis::NegX) << axis_name(b.axis);
      EXPECT_TRUE(is_height_field(b.mesh, axis_direction(b.axis)));
    }
  EXPECT_LE(blocks_overlap(r.blocks[0].mesh, r.blocks[1].mesh), 1e-9);
  // Without the cube, the same merge takes +-z (the first direction tried).
  const ToleranceMergeResult free = merge_within_tolerance(voxel_mesh(grooved_box_cells()), halves(grooved_box_cells()), o);
  ASSERT_EQ(free.blocks.size(), 1u);
  EXPECT_TRUE(free.blocks[0].axis == Axis::PosZ || free.blocks[0].axis == Axis::NegZ);
}

TEST(MergeWithinTolerance, RejectsANonPositiveTolerance) {
  const Mesh solid = voxel_mesh(grooved_box_cells());
  EXPECT_THROW(merge_within_tolerance(solid, halves(grooved_box_cells()), {}), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
