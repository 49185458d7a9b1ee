// SPDX-License-Identifier: GPL-3.0-or-later
// Decomposition within a tolerance by allowances (issue 17, point 2):
// tolerance_allowances() on the grooved box, and decompose() end to end.
#include "subfab/decompose/tolerance_allowances.h"

#include <gtest/gtest.h>

#include "subfab/core/error.h"
#include "subfab/decompose/decompose.h"
#include "subfab/validate/validate_decomposition.h"
#include "support/groove_shapes.h"
#include "support/test_shapes.h"

namespace subfab {
namespace {

using test::grooved_box_cells;
using test::voxel_mesh;

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

}  // namespace
}  // namespace subfab
