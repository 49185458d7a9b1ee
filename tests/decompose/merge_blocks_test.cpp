// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/merge_blocks.h"

#include <gtest/gtest.h>

#include "decompose/block_test_shapes.h"
#include "subfab/decompose/validate_decomposition.h"

namespace subfab {
namespace {

using test::box_solid;

Block make_block(const Mesh& m, Axis axis, int source) { return Block{m, axis, source}; }

TEST(MergeBlocks, SideBySideOnOneBaseMerge) {
  const MergeResult r = merge_blocks({make_block(box_solid({0, 0, 0}, {1, 1, 1}), Axis::PosZ, 0),
                                      make_block(box_solid({1, 0, 0}, {2, 1, 1}), Axis::PosZ, 1)});
  ASSERT_EQ(r.blocks.size(), 1u);
  EXPECT_EQ(r.num_merges, 1u);
  EXPECT_NEAR(signed_volume(r.blocks[0].mesh), 2.0, 1e-12);
  EXPECT_TRUE(check_closed_solid(r.blocks[0].mesh).ok());
  EXPECT_TRUE(is_height_field(r.blocks[0].mesh, Vec3::UnitZ()));
  EXPECT_EQ(r.blocks[0].source_box, 0);
}

TEST(MergeBlocks, DifferentDirectionsDoNotMerge) {
  const MergeResult r = merge_blocks({make_block(box_solid({0, 0, 0}, {1, 1, 1}), Axis::PosZ, 0),
                                      make_block(box_solid({1, 0, 0}, {2, 1, 1}), Axis::PosX, 1)});
  EXPECT_EQ(r.blocks.size(), 2u);
  EXPECT_EQ(r.num_merges, 0u);
}

TEST(MergeBlocks, StackedBlockMergesOnlyWhereTheUnionIsAHeightField) {
  // A step: a 2 x 1 x 1 slab with a 1 x 1 x 1 cube standing on its left half.
  const Mesh slab = box_solid({0, 0, 0}, {2, 1, 1});
  const Mesh cube = box_solid({0, 0, 1}, {1, 1, 2});
  // Milled from +z: the cube's base is glued onto the slab's top: one valid block.
  MergeResult up = merge_blocks({make_block(slab, Axis::PosZ, 0), make_block(cube, Axis::PosZ, 1)});
  ASSERT_EQ(up.blocks.size(), 1u);
  EXPECT_NEAR(signed_volume(up.blocks[0].mesh), 3.0, 1e-12);
  EXPECT_TRUE(is_height_field(up.blocks[0].mesh, Vec3::UnitZ()));
  // Milled from -z: the union would face +z at two levels: not merged.
  MergeResult down = merge_blocks({make_block(slab, Axis::NegZ, 0), make_block(cube, Axis::NegZ, 1)});
  EXPECT_EQ(down.blocks.size(), 2u);
  // Height limit 1.5: the union (height 2) is too tall.
  MergeOptions limited;
  limited.max_height = 1.5;
  EXPECT_EQ(merge_blocks({make_block(slab, Axis::PosZ, 0), make_block(cube, Axis::PosZ, 1)}, limited).blocks.size(), 2u);
}

TEST(MergeBlocks, BlocksThatOnlyTouchAlongAnEdgeStayApart) {
  const MergeResult r = merge_blocks({make_block(box_solid({0, 0, 0}, {1, 1, 1}), Axis::PosZ, 0),
                                      make_block(box_solid({1, 1, 0}, {2, 2, 1}), Axis::PosZ, 1)});
  EXPECT_EQ(r.blocks.size(), 2u);
}

TEST(MergeBlocks, ChainOfThreeBecomesOne) {
  const MergeResult r = merge_blocks({make_block(box_solid({0, 0, 0}, {1, 1, 1}), Axis::PosY, 0),
                                      make_block(box_solid({1, 0, 0}, {2, 1, 1}), Axis::PosY, 1),
                                      make_block(box_solid({2, 0, 0}, {3, 1, 1}), Axis::PosY, 2)});
  ASSERT_EQ(r.blocks.size(), 1u);
  EXPECT_NEAR(signed_volume(r.blocks[0].mesh), 3.0, 1e-12);
}

}  // namespace
}  // namespace subfab
