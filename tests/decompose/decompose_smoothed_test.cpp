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

TEST(DecomposeSmoothed, RejectsAnOverhangAllowance) {
  SmoothedDecomposeOptions o = options_for_test(0.01, 10);
  o.decompose.max_overhang_deg = 10;
  EXPECT_THROW(decompose_smoothed(bumped_cube(4, 0.1), o), InvalidArgumentError);
}

// --smooth with --tolerance: the smoothed model decomposed within the
// tolerance, nothing restored; the blocks lie within the smoothing's largest
// move plus the tolerance's measured bound of the ORIGINAL input (checked
// here by validate's check 10 against the original at that bound, every
// other check passing there too).
TEST(DecomposeSmoothed, WithinAToleranceTheDeviationsAddUp) {
  const Mesh input = bumped_cube(12, 0.25, 0.2);
  SmoothedDecomposeOptions o = options_for_test(0.01, 20);
  o.decompose.tolerance_fraction = 0.05;
  const SmoothedDecomposeResult within = decompose_smoothed(input, o);
  const SmoothedDecomposeReport& rep = within.report;
  EXPECT_TRUE(rep.within_tolerance);
  // the same smoothed model decomposed exactly (its undercut repaired)
  const DecomposeResult exact = decompose(within.smoothed, options_for_test(0.01, 20).decompose);
  // measured: 40 exact blocks, 1 within the tolerance, bound 0.029 x diagonal (smoothing 0.01)
  EXPECT_LT(rep.num_blocks, exact.blocks.size());  // the undercut is filled within the tolerance
  EXPECT_DOUBLE_EQ(rep.tolerance, 0.05 * rep.bbox_diagonal);  // of the input's diagonal
  EXPECT_LE(rep.decomposed_deviation, 0.01 * rep.bbox_diagonal * (1 + 1e-12));
  EXPECT_GE(rep.decomposed_deviation, rep.smooth.hausdorff - rep.smooth.hausdorff_error);
  EXPECT_GT(rep.max_deviation, rep.decomposed_deviation);  // the fill deviates too
  EXPECT_LE(rep.max_deviation, rep.decomposed_deviation + rep.tolerance);
  const DecomposeResult& d = within.decomposition;
  ASSERT_TRUE(d.repaired_input.has_value());
  EXPECT_EQ(d.repaired_input->vertices, within.smoothed.vertices);  // the blocks decompose the smoothed model
  for (const Block& b : d.blocks) EXPECT_TRUE(is_height_field(b.mesh, axis_direction(b.axis)));
  // against the smoothed model within T, and against the input within the bound
  const std::vector<ValidationBlock> blocks = test::to_validation(make_exported_blocks(within.smoothed, d));
  for (const auto& [model, tolerance] : {std::pair{&within.smoothed, rep.tolerance}, std::pair{&input, rep.max_deviation}}) {
    ValidationOptions vo;
    vo.tolerance = tolerance;
    const ValidationReport report = validate_decomposition(*model, blocks, vo);
    for (const CheckReport& c : report.checks)
      EXPECT_TRUE(c.passed) << c.name << ": " << (c.failures.empty() ? c.summary : c.failures[0]);
  }
}

}  // namespace
}  // namespace subfab
