// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/merge_within_tolerance.h"

#include <gtest/gtest.h>

#include "decompose/block_pairs_detail.h"
#include "geometry/solid_index.h"

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

TEST(MergeWithinTolerance, AFillProvenToMissABlockNeedsNoBooleanAndOneReachingItCollides) {
  // The merges' collision check with what the milled shape adds (its fill,
  // in boxes): against the L prism (the union of [0,2]x[0,1] and [0,1]x[0,2]
  // in xy, z in [0,1]; its notch [1,2]^2 is empty). Here each shape is all
  // fill (its carved part empty), covered by its own box.
  const std::vector<Block> blocks{Block{test::l_solid(), Axis::PosZ, 0}};
  const std::vector<BoundingBox> boxes = detail::block_boxes(blocks);
  const std::vector<double> volumes = detail::block_volumes(blocks);
  const std::unique_ptr<detail::SolidIndex> index = detail::inside_test_index(blocks[0].mesh);
  ASSERT_NE(index, nullptr);
  int asked = 0;
  const auto check = [&](const Mesh& m, const std::vector<BoundingBox>& fill, bool proof) {
    const detail::AddedFill added{&fill, &fill, [&](std::size_t k) {
                                    EXPECT_EQ(k, 0u);
                                    ++asked;
                                    return index.get();
                                  }};
    return detail::overlaps_a_block(m, blocks, boxes, volumes, nullptr, 1e-6, proof ? &added : nullptr);
  };
  // In the notch: its box meets the prism's, its interior misses the prism:
  // proven apart (the index asked once), as the exact check finds.
  const Mesh in_notch = test::box_solid({1.2, 1.2, 0}, {1.8, 1.8, 1});
  EXPECT_FALSE(check(in_notch, {bounding_box(in_notch)}, true));
  EXPECT_EQ(asked, 1);
  EXPECT_FALSE(check(in_notch, {bounding_box(in_notch)}, false));
  // Across the arm x in [0.8, 1]: 0.12 of it inside the prism, a collision
  // both ways.
  const Mesh across = test::box_solid({0.8, 1.2, 0}, {1.8, 1.8, 1});
  EXPECT_TRUE(check(across, {bounding_box(across)}, true));
  EXPECT_EQ(asked, 2);
  EXPECT_TRUE(check(across, {bounding_box(across)}, false));
  // A tall shape standing in the notch whose fill lies above z = 1 (its
  // carved part is the notch's height): the fill does not reach into the
  // prism's box, so the pair is not checked at all (the index not asked).
  const Mesh tall = test::box_solid({1.2, 1.2, 0}, {1.8, 1.8, 3});
  EXPECT_FALSE(check(tall, {BoundingBox{Vec3(1.2, 1.2, 1), Vec3(1.8, 1.8, 3)}}, true));
  EXPECT_EQ(asked, 2);
  EXPECT_FALSE(check(tall, {bounding_box(tall)}, true));  // all fill: proven apart
  EXPECT_EQ(asked, 3);
}

TEST(MergeWithinTolerance, RejectsANonPositiveTolerance) {
  const Mesh solid = voxel_mesh(grooved_box_cells());
  EXPECT_THROW(merge_within_tolerance(solid, halves(grooved_box_cells()), {}), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
