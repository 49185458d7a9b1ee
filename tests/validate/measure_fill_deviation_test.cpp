// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/validate/measure_fill_deviation.h"

#include <gtest/gtest.h>

#include "subfab/core/error.h"
#include "support/groove_shapes.h"

namespace subfab {
namespace {

using test::cells_of_box;
using test::grooved_box_cells;
using test::voxel_mesh;

TEST(MeasureFillDeviation, FillingAGrooveMovesTheSurfaceByItsDepth) {
  const Mesh solid = voxel_mesh(grooved_box_cells());
  const Mesh full = voxel_mesh(cells_of_box({0, 0, 0}, {10, 10, 10}));
  const FillDeviationMeter meter(solid);
  const FillDeviation d = meter.measure(full, {}, {.reach = 1.5, .error = 0.01});
  ASSERT_TRUE(d.failure.empty()) << d.failure;
  EXPECT_NEAR(d.to_input, 1.0, 0.01);
  EXPECT_NEAR(d.from_input, 1.0, 0.01);
  EXPECT_NEAR(d.bound(), 1.0 + 0.01, 0.01 + 1e-12);
}

TEST(MeasureFillDeviation, ABlockInsideTheSolidDeviatesNothing) {
  const Mesh solid = voxel_mesh(cells_of_box({0, 0, 0}, {4, 4, 4}));
  const Mesh inner = voxel_mesh(cells_of_box({0, 0, 0}, {2, 4, 4}));
  const FillDeviationMeter meter(solid);
  const FillDeviation d = meter.measure(inner, {}, {.reach = 0.5, .error = 1e-3});
  ASSERT_TRUE(d.failure.empty()) << d.failure;
  EXPECT_LE(d.to_input, 1e-3);
  EXPECT_LE(d.from_input, 1e-3);
}

TEST(MeasureFillDeviation, ABlockStickingOutIsMeasuredFromItsFarthestPoint) {
  // A 1 x 2 plate through the top of a cube, standing 3 out of it: its top
  // is 3 above the cube's top face; the cube's top face under the plate is
  // buried at most 0.5 (the middle of the plate's 1-wide footprint).
  const Mesh solid = voxel_mesh(cells_of_box({0, 0, 0}, {4, 4, 4}));
  const Mesh plate = voxel_mesh(cells_of_box({1, 1, 0}, {2, 3, 7}));
  const FillDeviationMeter meter(solid);
  const FillDeviation d = meter.measure(plate, {}, {.reach = 4.0, .error = 1e-3});
  ASSERT_TRUE(d.failure.empty()) << d.failure;
  EXPECT_NEAR(d.to_input, 3.0, 1e-3);
  EXPECT_NEAR(d.from_input, 0.5, 1e-3);
}

TEST(MeasureFillDeviation, RejectsABadErrorBound) {
  const Mesh solid = voxel_mesh(cells_of_box({0, 0, 0}, {2, 2, 2}));
  const FillDeviationMeter meter(solid);
  EXPECT_THROW(meter.measure(solid, {}, {.reach = 1.0, .error = 0.0}), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
