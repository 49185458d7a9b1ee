// SPDX-License-Identifier: GPL-3.0-or-later
#include "unfold/fidelity_band.h"

#include <gtest/gtest.h>

#include "subfab/core/error.h"
#include "subfab/unfold/apply_masks.h"
#include "subfab/unfold/marching_cubes.h"
#include "geometry/hausdorff_distance.h"

namespace subfab {
namespace {

// Triangles of the surface of the box [lo, hi] (outward).
void add_box(Mesh& m, const Vec3& lo, const Vec3& hi) {
  const int base = static_cast<int>(m.vertices.size());
  for (int k = 0; k < 8; ++k)
    m.vertices.emplace_back((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.faces.push_back({base + q[0], base + q[1], base + q[2]});
    m.faces.push_back({base + q[0], base + q[2], base + q[3]});
  }
}

// A known lattice (spacing 1, origin 0): the block [2, 6]^3 of inside points
// with a one-point-thin pillar (4, 4, 7..9) on top, and the input it samples:
// the box [1.5, 6.5]^3 and the pillar [3.8, 4.2]^2 x [6.5, 9.2] (a triangle
// soup is enough: the band only samples the input's surface).
struct Pillar {
  Lattice lattice;
  Mesh input;
  Pillar() {
    lattice.grid.size = {12, 12, 12};
    lattice.inside.assign(lattice.grid.num_points(), 0);
    for (int k = 2; k <= 6; ++k)
      for (int j = 2; j <= 6; ++j)
        for (int i = 2; i <= 6; ++i) lattice.inside[lattice.grid.index(i, j, k)] = 1;
    for (int k = 7; k <= 9; ++k) lattice.inside[lattice.grid.index(4, 4, k)] = 1;
    add_box(input, Vec3(1.5, 1.5, 1.5), Vec3(6.5, 6.5, 6.5));
    add_box(input, Vec3(3.8, 3.8, 6.5), Vec3(4.2, 4.2, 9.2));
  }
  std::size_t at(int i, int j, int k) const { return lattice.grid.index(i, j, k); }
};

// Lowering the pillar's top by one point leaves its tip (z = 9.2) 0.7 from
// the new top vertex (4, 4, 8.5): allowed. Lowering it once more would put
// the tip 2.7 spacings from the surface: refused.
TEST(FidelityBand, RefusesAFlipThatMovesTheSurfaceTooFar) {
  Pillar p;
  std::vector<std::uint8_t> inside = p.lattice.inside;
  unfold_detail::FidelityBand band(p.input, p.lattice.grid, inside, 1.5);
  EXPECT_GT(band.num_constraints(), 0u);
  inside[p.at(4, 4, 9)] = 0;
  EXPECT_TRUE(band.allows(inside, {p.at(4, 4, 9)}));
  band.commit(inside, {p.at(4, 4, 9)});
  inside[p.at(4, 4, 8)] = 0;
  EXPECT_FALSE(band.allows(inside, {p.at(4, 4, 8)}));
  // Both at once: refused as well.
  unfold_detail::FidelityBand fresh(p.input, p.lattice.grid, p.lattice.inside, 1.5);
  EXPECT_FALSE(fresh.allows(inside, {p.at(4, 4, 9), p.at(4, 4, 8)}));
  // A wider band (3 spacings) accepts the second flip.
  unfold_detail::FidelityBand wide(p.input, p.lattice.grid, p.lattice.inside, 3.0);
  EXPECT_TRUE(wide.allows(inside, {p.at(4, 4, 9), p.at(4, 4, 8)}));
  // Flips far from the input touch no constraint.
  std::vector<std::uint8_t> far = p.lattice.inside;
  far[p.at(10, 10, 1)] = 1;
  EXPECT_TRUE(band.allows(far, {p.at(10, 10, 1)}));
  EXPECT_THROW(unfold_detail::FidelityBand(p.input, p.lattice.grid, inside, 0.0), InvalidArgumentError);
}

// The mask stage on the same lattice: without the input it grinds the
// pillar down (pyramid masks, one point at a time); with it, the pillar
// keeps its lower points and the input stays within the band.
TEST(FidelityBand, MaskStageKeepsTheThinPillar) {
  Pillar p;
  const MaskResult free = apply_masks(p.lattice, {});
  EXPECT_FALSE(free.lattice.is_inside(4, 4, 8));
  const MaskResult kept = apply_masks(p.lattice, {.reference = &p.input});
  EXPECT_TRUE(kept.lattice.is_inside(4, 4, 8));
  EXPECT_TRUE(kept.lattice.is_inside(4, 4, 7));
  EXPECT_GT(kept.num_rejected_fidelity, 0u);
  const detail::SurfaceDistance to_surface(kept.surface.mesh);
  for (const Vec3& v : p.input.vertices) EXPECT_LE(to_surface(v), 1.5) << v.transpose();
  const detail::SurfaceDistance to_free(free.surface.mesh);
  EXPECT_GT(to_free(Vec3(4.2, 4.2, 9.2)), 1.5);  // what the band prevents
  EXPECT_THROW(apply_masks(p.lattice, {.reference = &p.input, .fidelity_radius = -1}), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
