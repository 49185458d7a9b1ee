// SPDX-License-Identifier: GPL-3.0-or-later
// decompose_smoothed(): smooth, decompose, restore the details, carve again
// (thesis 4.3.5), then every check of validate_decomposition() against the
// restored solid.
#include "subfab/decompose/decompose_smoothed.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/exact_normal_signs.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/export_decomposition.h"
#include "subfab/decompose/finalize_blocks.h"
#include "subfab/validate/validate_decomposition.h"
#include "support/block_test_shapes.h"
#include "support/smooth_test_shapes.h"

namespace subfab {
namespace {

using test::bumped_cube;

SmoothedDecomposeOptions options_for_test(double cap, int passes) {
  SmoothedDecomposeOptions o;
  o.decompose.orient = false;
  o.smooth.max_deviation = cap;
  o.smooth.num_passes = passes;
  return o;
}

//! Every check of validate_decomposition() passes against the restored solid.
void expect_valid(const SmoothedDecomposeResult& r) {
  const DecomposeResult& d = r.decomposition;
  ASSERT_TRUE(d.repaired_input.has_value());
  const Mesh& restored = *d.repaired_input;
  const ValidationReport report =
      validate_decomposition(restored, test::to_validation(make_exported_blocks(restored, d)), {});
  for (const CheckReport& c : report.checks)
    EXPECT_TRUE(c.passed) << c.name << ": " << (c.failures.empty() ? c.summary : c.failures[0]);
}

TEST(DecomposeSmoothed, BumpOnABoxIsPartlyRestoredAndValid) {
  const Mesh input = bumped_cube(8, 0.2);
  const SmoothedDecomposeResult r = decompose_smoothed(input, options_for_test(0.05, 60));
  const SmoothedDecomposeReport& rep = r.report;
  EXPECT_GT(rep.smooth.hausdorff, 0.02 * rep.bbox_diagonal);  // the smoothing flattened the bump
  // (and rounded the cube's edges and corners, which costs blocks: a cube is no case for smoothing)
  EXPECT_LE(rep.num_blocks, rep.num_blocks_smoothed);  // the restoration brings no block back
  EXPECT_LT(rep.mean_deviation, 0.8 * rep.smoothed_mean_deviation);  // detail is back
  EXPECT_GT(rep.restore.num_held_on_box + rep.restore.num_held_back, 0);
  expect_valid(r);
}

TEST(DecomposeSmoothed, LeaningBumpIsRestoredWithoutItsUndercut) {
  const Mesh input = bumped_cube(12, 0.25, 0.2);
  const SmoothedDecomposeResult r = decompose_smoothed(input, options_for_test(0.1, 100));
  const SmoothedDecomposeReport& rep = r.report;
  // (smoothing rounds the cube's edges, which costs blocks here: no fewer blocks than exact)
  EXPECT_LE(rep.num_blocks, rep.num_blocks_smoothed);  // the restoration brings no block back
  EXPECT_GT(rep.restore.num_held_back, 0);              // (faces of the undercut were held back)
  EXPECT_LT(rep.mean_deviation, 0.9 * rep.smoothed_mean_deviation);  // some of the detail is back
  EXPECT_GT(rep.max_deviation, 0.0);                        // not all of it: the undercut cannot be milled
  expect_valid(r);
}

TEST(DecomposeSmoothed, SameBlocksOnOneThread) {
  const Mesh input = bumped_cube(12, 0.25, 0.2);
  const SmoothedDecomposeOptions o = options_for_test(0.1, 100);
  const SmoothedDecomposeResult many = decompose_smoothed(input, o);
  SmoothedDecomposeResult one;
  {
    ThreadLimit limit(1);
    one = decompose_smoothed(input, o);
  }
  EXPECT_EQ(one.decomposition.repaired_input->vertices, many.decomposition.repaired_input->vertices);
  ASSERT_EQ(one.decomposition.blocks.size(), many.decomposition.blocks.size());
  for (std::size_t i = 0; i < one.decomposition.blocks.size(); ++i)
    EXPECT_EQ(one.decomposition.blocks[i].mesh.vertices, many.decomposition.blocks[i].mesh.vertices);
}

TEST(DecomposeSmoothed, RejectsATolerance) {
  SmoothedDecomposeOptions o = options_for_test(0.01, 10);
  o.decompose.tolerance_fraction = 1e-3;
  EXPECT_THROW(decompose_smoothed(bumped_cube(4, 0.1), o), InvalidArgumentError);
  o = options_for_test(0.01, 10);
  o.decompose.max_overhang_deg = 10;
  EXPECT_THROW(decompose_smoothed(bumped_cube(4, 0.1), o), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
