// SPDX-License-Identifier: GPL-3.0-or-later
// Regression: kitten --max-height 0.05, block 040's machine STL
// self-intersected once rounded to float32 (issue 17); export now cleans it.
#include "decompose/single_precision_cleanup.h"

#include <gtest/gtest.h>

#include "subfab/decompose/export_decomposition.h"
#include "subfab/mesh/read_mesh.h"
#include "subfab/validate/check_single_precision.h"
#include "support/block_test_shapes.h"
#include "support/test_support.h"

namespace subfab {
namespace {

using test::float32_frustum;

TEST(SinglePrecisionCleanup, VertexRoundedThroughAFaceIsRoundedTheOtherWay) {
  Mesh machine = float32_frustum(), block = float32_frustum();
  ASSERT_FALSE(check_single_precision(machine).ok());
  const detail::SinglePrecisionCleanup r = detail::clean_single_precision(machine, block);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.num_collapsed, 0u);
  EXPECT_GE(r.num_nudged, 1u);
  EXPECT_TRUE(check_single_precision(machine).ok());
  // Every machine coordinate is a float within one float spacing of the original.
  const Mesh original = float32_frustum();
  for (std::size_t v = 0; v < machine.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(machine.vertices[v][k], static_cast<double>(static_cast<float>(machine.vertices[v][k])));
      EXPECT_LE(std::abs(machine.vertices[v][k] - original.vertices[v][k]), 1.2e-7);
    }
  EXPECT_EQ(block.faces, machine.faces);  // the block keeps the machine mesh's faces
}

TEST(SinglePrecisionCleanup, SolidMeshIsLeftAlone) {
  Mesh machine = test::box_solid({0, 0, 0}, {1, 2, 3}), block = machine;
  const detail::SinglePrecisionCleanup r = detail::clean_single_precision(machine, block);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.num_collapsed + r.num_nudged + r.num_faces_removed, 0u);
  EXPECT_EQ(machine.vertices, test::box_solid({0, 0, 0}, {1, 2, 3}).vertices);
}

TEST(SinglePrecisionCleanup, SheetThinnerThanAFloatIsReported) {
  // Issue 17's 4.3 x 2.4 x 1.3e-7 sheet, at z = 1 (thinner than float32's
  // spacing there): it collapses entirely, which no rounding can save.
  Mesh machine = test::box_solid({0, 0, 1}, {4.3, 2.4, 1 + 4e-8}), block = machine;
  const detail::SinglePrecisionCleanup r = detail::clean_single_precision(machine, block);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.num_collapsed, 4u);
}

TEST(SinglePrecisionCleanup, ClusterOfNearlyCoincidentVerticesIsCollapsedAlongItsEdges) {
  // Regression: pinion.off at the default settings, block 761 (axis -x): box
  // planes cut a cluster of 9 vertices within 2e-8 of each other (edges down
  // to 1e-9) on the plane y = 0.2867; in float32 some of them weld, others
  // stay one float apart, and merging the welded ones left 10 non-manifold
  // edges, 4 zero-area faces and 7 crossing pairs (validate check 8 failed).
  Mesh block = read_mesh(test::data_path("regression/pinion_block_761.obj"));
  Mesh machine = machine_mesh_of(block, Axis::NegX, Eigen::Matrix3d::Identity());
  ASSERT_FALSE(check_single_precision(machine).ok());
  const Mesh original = machine;
  const detail::SinglePrecisionCleanup r = detail::clean_single_precision(machine, block);
  EXPECT_TRUE(r.ok);
  EXPECT_TRUE(check_single_precision(machine).ok());
  EXPECT_EQ(block.faces, machine.faces);
  EXPECT_EQ(block.num_vertices(), machine.num_vertices());
  // Only sub-float features went: a handful of vertices and their faces.
  EXPECT_LE(r.num_collapsed, 12u);
  EXPECT_GE(machine.num_faces() + 2 * 12, original.num_faces());
}

}  // namespace
}  // namespace subfab
