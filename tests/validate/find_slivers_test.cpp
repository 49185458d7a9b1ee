// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/validate/find_slivers.h"

#include <gtest/gtest.h>

#include "subfab/core/error.h"
#include "support/block_test_shapes.h"

namespace subfab {
namespace {

using test::box_solid;

TEST(FindSlivers, ThinLayerOfAThickModelIsASliver) {
  // A unit cube cut at z = 0.999: the top block is 1e-3 thick, the model 1.
  const Mesh cube = box_solid({0, 0, 0}, {1, 1, 1});
  const Mesh bottom = box_solid({0, 0, 0}, {1, 1, 0.999}), top = box_solid({0, 0, 0.999}, {1, 1, 1});
  const auto r = find_slivers(cube, {{&bottom}, {&top}}, {.min_thickness = 0.01});
  ASSERT_EQ(r.size(), 2u);
  EXPECT_FALSE(r[0].measured);
  EXPECT_FALSE(r[0].sliver);
  EXPECT_TRUE(r[1].measured);
  EXPECT_TRUE(r[1].sliver);
  EXPECT_NEAR(r[1].thickness.thickness, 1e-3, 1e-12);
  EXPECT_EQ(r[1].num_chords, 144u);
  EXPECT_NEAR(r[1].block_chord, 1e-3, 1e-12);
  EXPECT_NEAR(r[1].model_chord, 1.0, 1e-12);
}

TEST(FindSlivers, ThinModelMakesNoSliver) {
  // A plate 1e-3 thick decomposed into two halves side by side: each block
  // is as thin as the model there.
  const Mesh plate = box_solid({0, 0, 0}, {2, 1, 1e-3});
  const Mesh left = box_solid({0, 0, 0}, {1, 1, 1e-3}), right = box_solid({1, 0, 0}, {2, 1, 1e-3});
  const auto r = find_slivers(plate, {{&left}, {&right}}, {.min_thickness = 0.01});
  for (const SliverMeasure& m : r) {
    EXPECT_TRUE(m.measured);
    EXPECT_FALSE(m.sliver);
    EXPECT_GT(m.num_chords, 0u);
    EXPECT_NEAR(m.model_chord, 1e-3, 1e-12);
  }
}

TEST(FindSlivers, ThinLayerOnAThinPartOnlyIsNoSliver) {
  // A T: a thick base [0,1]^2 x [0,1] and a thin fin x in [1, 2], z in
  // [0, 0.005]. The fin as its own block is as thin as the model under it.
  Mesh model = box_solid({0, 0, 0}, {1, 1, 1});
  const Mesh base = model, fin = box_solid({1, 0, 0}, {2, 1, 0.005});
  // The model: base ∪ fin (a closed mesh of the union is not needed here:
  // the fin's lines never cross the base, so the two solids as one mesh do).
  const int offset = static_cast<int>(model.vertices.size());
  model.vertices.insert(model.vertices.end(), fin.vertices.begin(), fin.vertices.end());
  for (Triangle f : fin.faces) {
    for (int& v : f) v += offset;
    model.faces.push_back(f);
  }
  const auto r = find_slivers(model, {{&base}, {&fin}}, {.min_thickness = 0.01});
  EXPECT_FALSE(r[0].sliver);
  EXPECT_TRUE(r[1].measured);
  EXPECT_FALSE(r[1].sliver);
  EXPECT_NEAR(r[1].model_chord, 0.005, 1e-12);
}

TEST(FindSlivers, RejectsBadOptions) {
  const Mesh cube = box_solid({0, 0, 0}, {1, 1, 1});
  EXPECT_THROW(find_slivers(cube, {{&cube}}, {.min_thickness = 0.0}), InvalidArgumentError);
  EXPECT_THROW(find_slivers(cube, {{&cube}}, {.min_thickness = 1.0, .num_lines = 0}), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
