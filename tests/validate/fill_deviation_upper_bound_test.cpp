// SPDX-License-Identifier: GPL-3.0-or-later
// The surface upper bound of the fill deviation (issue 17, validate no
// slower than decompose): blocks sticking out of a cube, with known
// distances, their parts made by check 4's outside_part().
#include "subfab/validate/fill_deviation_upper_bound.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "subfab/core/error.h"
#include "support/box_shapes.h"
#include "validate/validate_booleans.h"

namespace subfab {
namespace {

using test::make_box_mesh;

constexpr double kError = 1e-3;
constexpr double kInf = std::numeric_limits<double>::infinity();

//! The parts of `blocks` outside `solid` (check 4), kept alive for the bound.
struct Parts {
  std::vector<detail::OutsidePart> parts;
  std::vector<FillPart> view;
  Parts(const Mesh& solid, const std::vector<const Mesh*>& blocks) {
    for (const Mesh* b : blocks) parts.push_back(detail::outside_part(*b, solid));
    for (const detail::OutsidePart& p : parts) {
      view.push_back({p.faces(), p.faces() ? &p.on_input : nullptr});
    }
  }
};

//! Area of the faces of `m` whose flag is `flag`.
double flagged_area(const Mesh& m, const std::vector<char>& flags, char flag) {
  double a = 0.0;
  for (std::size_t f = 0; f < m.faces.size(); ++f)
    if (flags[f] == flag) {
      const Vec3& p = m.vertices[static_cast<std::size_t>(m.faces[f][0])];
      const Vec3& q = m.vertices[static_cast<std::size_t>(m.faces[f][1])];
      const Vec3& r = m.vertices[static_cast<std::size_t>(m.faces[f][2])];
      a += 0.5 * (q - p).cross(r - p).norm();
    }
  return a;
}

//! The bound of one block alone, after checking its part: a closed mesh
//! with these areas on the input's surface and off it.
FillDeviationUpperBound bound_alone(const Mesh& solid, const Mesh& block, double on_input, double off_input) {
  const Parts p(solid, {&block});
  EXPECT_TRUE(p.parts[0].mesh.has_value());
  if (!p.parts[0].mesh) return {};
  EXPECT_NEAR(flagged_area(*p.parts[0].mesh, p.parts[0].on_input, 1), on_input, 1e-12);
  EXPECT_NEAR(flagged_area(*p.parts[0].mesh, p.parts[0].on_input, 0), off_input, 1e-12);
  return fill_deviation_upper_bounds(solid, {&block}, p.view, {.error = kError}).blocks.at(0);
}

// S = [0, 10]^3; F = [2, 4]^2 x [5, 13] sticks out 3 above S's top. Its part
// [2, 4]^2 x [10, 13] has its bottom (area 4) on S, the rest (4 + 24) outside.
// Its top lies 3 from S; the buried bottom's centre lies 1 from the part's
// sides, the nearest surface of S ∪ F there.
TEST(FillDeviationUpperBound, AColumnSticking3OutOfACubeIsBoundedBy3And1) {
  const Mesh solid = make_box_mesh(Vec3(0, 0, 0), Vec3(10, 10, 10));
  const Mesh column = make_box_mesh(Vec3(2, 2, 5), Vec3(4, 4, 13));
  // The column, and its part alone sitting on S's top face from outside,
  // [2, 4]^2 x [10, 13]: their boxes meet only on the plane, so its part is
  // the whole block, and its bottom lies on S (exactly, though it is a face
  // of the block): the same 3 and 1.
  for (const Mesh& block : {column, make_box_mesh(Vec3(2, 2, 10), Vec3(4, 4, 13))}) {
    const FillDeviationUpperBound alone = bound_alone(solid, block, 4.0, 28.0);
    EXPECT_GE(alone.to_input, 3.0);
    EXPECT_LE(alone.to_input, 3.0 + 2 * kError);
    EXPECT_GE(alone.from_input, 1.0);
    EXPECT_LE(alone.from_input, 1.0 + 2 * kError);
  }
  const Parts p(solid, {&column});
  const FillDeviationUpperBounds b = fill_deviation_upper_bounds(solid, {&column}, p.view, {.error = kError});
  ASSERT_EQ(b.blocks.size(), 1u);
  // Over the whole of ∂S (stop 0) as over the part's faces on it: the top's nearest points are on its rim.
  const FillDeviationUpperBound whole =
      fill_deviation_upper_bounds(solid, {&column}, p.view, {.error = kError, .stop = 0.0}).blocks[0];
  EXPECT_NEAR(whole.to_input, b.blocks[0].to_input, 2 * kError);
  EXPECT_GE(whole.to_input, 3.0);
  EXPECT_GT(b.target_faces, 0u);
  EXPECT_LT(b.target_faces, b.part_faces);  // not the bottom's
  // Not asked, or no part: not bounded.
  EXPECT_EQ(fill_deviation_upper_bounds(solid, {&column}, p.view, {.error = kError}, {0}).blocks[0].bound(),
            std::numeric_limits<double>::infinity());
  EXPECT_EQ(fill_deviation_upper_bounds(solid, {&column}, {FillPart{}}, {.error = kError}).blocks[0].bound(),
            std::numeric_limits<double>::infinity());
  EXPECT_THROW(fill_deviation_upper_bounds(solid, {&column}, {}, {.error = kError}), InvalidArgumentError);
  EXPECT_THROW(fill_deviation_upper_bounds(solid, {&column}, p.view, {.error = 0.0}), InvalidArgumentError);
  EXPECT_THROW(fill_deviation_upper_bounds(solid, {&column}, p.view, {.error = kError, .coarse_fraction = -1}),
               InvalidArgumentError);
}

// Two such blocks side by side, [2, 4] x [0, 8] and [4, 6] x [0, 8] in x, y:
// their parts meet on the plane x = 4, a face inside S ∪ F1 ∪ F2, not on its
// surface. The buried input under the contact, (4, y, 10), lies 2 from the
// nearest surface (x = 2 or x = 6): the bound must not take the contact face
// for surface (it would say 1, the half width of one part).
TEST(FillDeviationUpperBound, AFaceAgainstAnotherBlockIsNotOnTheModelMade) {
  const Mesh solid = make_box_mesh(Vec3(0, 0, 0), Vec3(10, 10, 10));
  const Mesh left = make_box_mesh(Vec3(2, 0, 5), Vec3(4, 8, 13));
  const Mesh right = make_box_mesh(Vec3(4, 0, 5), Vec3(6, 8, 13));
  const Parts p(solid, {&left, &right});
  const FillDeviationUpperBounds b = fill_deviation_upper_bounds(solid, {&left, &right}, p.view, {.error = kError});
  for (const FillDeviationUpperBound& x : b.blocks) {
    EXPECT_GE(x.to_input, 3.0);
    EXPECT_LE(x.to_input, 3.0 + 2 * kError);
    EXPECT_GE(x.from_input, 2.0);
    EXPECT_LE(x.from_input, 2.0 + 2 * kError);
  }
  // Alone, each is bounded by its own half width.
  const Parts alone(solid, {&left});
  EXPECT_LE(fill_deviation_upper_bounds(solid, {&left}, alone.view, {.error = kError}).blocks[0].from_input,
            1.0 + 2 * kError);
}

// A milled shape filling a notch: S = [0, 10]^3 with x, y in [3, 7], z in
// [6, 10] cut away; F = [1, 9]^2 x [2, 10]. The part is the notch; its floor
// and walls are the buried input, its top (z = 10) the model made. The
// floor's centre lies 4 under that top (as the sampled lower bound finds);
// the top's centre lies 2 from the notch's walls.
TEST(FillDeviationUpperBound, AFilledNotchIsBoundedByItsDepth) {
  const Mesh solid = test::make_notched_cube();
  const Mesh fill = make_box_mesh(Vec3(1, 1, 2), Vec3(9, 9, 10));
  const FillDeviationUpperBound b = bound_alone(solid, fill, 16.0 + 64.0, 16.0);  // the notch's floor, walls; top
  EXPECT_GE(b.to_input, 2.0);
  EXPECT_LE(b.to_input, 2.0 + 2 * kError);
  EXPECT_GE(b.from_input, 4.0);
  EXPECT_LE(b.from_input, 4.0 + 2 * kError);
}

// outside_part() clipped to a box known to hold the part (the mill stage: a
// milled shape's fill boxes, widened) gives the same part: the column
// [2, 4]^2 x [5, 13] in S = [0, 10]^3, clipped to a box round its part
// [2, 4]^2 x [10, 13] that cuts it at z = 9.5 (and one beyond it in x, y).
TEST(FillDeviationUpperBound, ThePartOutsideClippedNearItIsTheSame) {
  const Mesh solid = make_box_mesh(Vec3(0, 0, 0), Vec3(10, 10, 10));
  const Mesh column = make_box_mesh(Vec3(2, 2, 5), Vec3(4, 4, 13));
  BoundingBox within;
  within.extend(Vec3(1.5, 1.5, 9.5));
  within.extend(Vec3(4.5, 4.5, 13.5));
  const detail::OutsidePart whole = detail::outside_part(column, solid);
  const detail::OutsidePart near = detail::outside_part(column, solid, &within);
  ASSERT_TRUE(whole.mesh.has_value());
  ASSERT_TRUE(near.mesh.has_value());
  EXPECT_NEAR(near.volume, whole.volume, 1e-12);  // rounded from differently triangulated faces
  EXPECT_NEAR(near.volume, 12.0, 1e-12);
  EXPECT_NEAR(flagged_area(*near.mesh, near.on_input, 1), 4.0, 1e-12);   // its bottom, on S's top
  EXPECT_NEAR(flagged_area(*near.mesh, near.on_input, 0), 28.0, 1e-12);  // its sides and top
  EXPECT_EQ(bounding_box(*near.mesh).min, bounding_box(*whole.mesh).min);
  EXPECT_EQ(bounding_box(*near.mesh).max, bounding_box(*whole.mesh).max);
}

}  // namespace
}  // namespace subfab
