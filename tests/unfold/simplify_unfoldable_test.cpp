// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/simplify_unfoldable.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "subfab/core/error.h"
#include "subfab/mesh/read_mesh.h"
#include "subfab/unfold/lattice_directions.h"
#include "support/test_support.h"

namespace subfab {
namespace {

// The acceptance properties of issue 4, on a real model.
void expect_acceptance(const Mesh& input, const SimplifyUnfoldableResult& r) {
  EXPECT_EQ(check_poly_mesh(r.mesh, r.origin, r.spacing), "");  // closed, oriented, no coplanar neighbours, ...
  for (const Facet& f : r.mesh.facets) {
    ASSERT_GE(f.normal, 0);
    // the facet's own (Newell) normal is that lattice direction
    Vec3 n = Vec3::Zero();
    const auto& l = f.loops[0];
    for (std::size_t i = 0; i < l.size(); ++i) n += r.mesh.vertices[l[i]].cross(r.mesh.vertices[l[(i + 1) % l.size()]]);
    EXPECT_EQ(lattice_direction_index(n, 1e-9), f.normal);
  }
  std::set<int> seen;
  for (const Net& net : r.unfolding.nets)
    for (int f : net.facets) EXPECT_TRUE(seen.insert(f).second);
  EXPECT_EQ(seen.size(), r.mesh.num_facets());
  EXPECT_EQ(find_net_overlap(r.unfolding), "");
  EXPECT_LE(refold_error(r.mesh, r.unfolding), 1e-9 * bounding_box(input).diagonal());
  EXPECT_GT(r.summary.hausdorff, 0.0);
  // deletion keeps the surface within 2 grid spacings of the input, or no
  // farther than the mask stage already put it
  EXPECT_LE(r.summary.hausdorff, std::max(2.0 * r.spacing, r.hausdorff_after_masks));
  EXPECT_GE(r.summary.facets_mc, r.summary.facets_after_masks);
  EXPECT_GE(r.summary.facets_after_masks, r.summary.facets_final);
  EXPECT_EQ(r.summary.facets_final, r.mesh.num_facets());
  EXPECT_EQ(r.summary.nets, r.unfolding.nets.size());
}

// Issue 4 on a real model at default settings, Hausdorff bound included:
// before the fidelity band of the mask stage, the ears of this bunny were
// eaten away (6.1 grid spacings).
TEST(SimplifyUnfoldable, BunnyMeetsTheAcceptanceProperties) {
  const Mesh bunny = read_mesh(test::data_path("bunny_lowres.off"));
  const auto r = simplify_unfoldable(bunny);
  expect_acceptance(bunny, r);
  EXPECT_LE(r.summary.hausdorff, 2.0 * r.spacing);
  EXPECT_LE(r.hausdorff_after_masks, 1.5 * r.spacing);
  EXPECT_LT(r.summary.facets_after_masks, r.summary.facets_mc / 2);  // the masks still do their job
  EXPECT_LT(r.summary.facets_final, r.summary.facets_after_masks);  // small facets did go
  EXPECT_NEAR(r.min_facet_area, 4 * r.spacing * r.spacing, 1e-15);
}

TEST(SimplifyUnfoldable, WithoutMasksStaysWithinTwoSpacings) {
  const Mesh bunny = read_mesh(test::data_path("bunny_lowres.off"));
  const auto r = simplify_unfoldable(bunny, {.masks = false});
  expect_acceptance(bunny, r);
  EXPECT_EQ(r.summary.facets_mc, r.summary.facets_after_masks);
  EXPECT_LE(r.summary.hausdorff, 2.0 * r.spacing);
}

TEST(SimplifyUnfoldable, ExplicitIdsAndNoAutomaticDeletion) {
  const Mesh part = read_mesh(test::data_path("part.off"));
  const auto plain = simplify_unfoldable(part, {.granularity = 1, .min_facet_area = 0});
  expect_acceptance(part, plain);
  EXPECT_EQ(plain.summary.facets_final, plain.summary.facets_after_masks);
  // delete every facet by id: those whose hole can be closed go, the rest are reported
  std::vector<int> ids;
  for (std::size_t f = 0; f < plain.mesh.num_facets(); f += 7) ids.push_back(int(f));
  const auto some = simplify_unfoldable(part, {.granularity = 1, .min_facet_area = 0, .delete_facet_ids = ids});
  expect_acceptance(part, some);
  EXPECT_TRUE(some.summary.facets_final < plain.summary.facets_final || !some.failures.empty());
  EXPECT_THROW(simplify_unfoldable(part, {.granularity = 1, .min_facet_area = 0, .delete_facet_ids = {100000}}), InvalidArgumentError);
  EXPECT_THROW(simplify_unfoldable(part, {.granularity = 0}), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
