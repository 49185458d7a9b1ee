// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/apply_masks.h"

#include <gtest/gtest.h>

#include <map>
#include <numeric>
#include <random>
#include <set>

#include "subfab/checks/check_boundary_edges.h"
#include "subfab/checks/check_consistent_orientation.h"
#include "subfab/checks/check_non_manifold_edges.h"
#include "subfab/checks/check_self_intersections.h"
#include "subfab/core/parallel.h"
#include "subfab/mesh/read_mesh.h"
#include "subfab/unfold/lattice_directions.h"
#include "support/test_support.h"
#include "support/unfold_test_shapes.h"
#include "geometry/hausdorff_distance.h"
#include "unfold/mask_catalogue.h"

namespace subfab {
namespace {

// Appendix A: 18 mask types, 340 oriented masks, and the per-figure counts
// of the captions (A.1 24, A.2 24, A.3 48, A.4 48, A.5 24, A.6 24, A.7 48,
// A.8 12, A.9 24, A.10 16, A.11 48). Our base types are read from the
// captions (the figures are missing), so these counts are what ties them to
// the thesis.
TEST(MaskCatalogue, CountsMatchAppendixA) {
  EXPECT_EQ(masks::oriented_masks().size(), 340u);
  std::map<std::string, std::size_t> per_figure;
  const auto counts = masks::orientations_per_base_type();
  for (std::size_t t = 0; t < counts.size(); ++t) per_figure[masks::base_types()[t].figure] += counts[t];
  const std::map<std::string, std::size_t> expected{{"A.1", 24}, {"A.2", 24}, {"A.3", 48}, {"A.4", 48},
                                                    {"A.5", 24}, {"A.6", 24}, {"A.7", 48}, {"A.8", 12},
                                                    {"A.9", 24}, {"A.10", 16}, {"A.11", 48}};
  EXPECT_EQ(per_figure, expected);
  const auto classes = masks::rotation_classes_per_base_type();
  EXPECT_EQ(std::accumulate(classes.begin(), classes.end(), std::size_t{0}), 18u);
  // A.1-A.7 have several POI sets, A.8-A.11 one.
  for (const auto& m : masks::oriented_masks()) {
    const std::string& fig = masks::base_types()[static_cast<std::size_t>(m.base_type)].figure;
    static const std::set<std::string> kSeveral{"A.1", "A.2", "A.3", "A.4", "A.5", "A.6", "A.7"};
    const bool several = kSeveral.count(fig) == 1;
    EXPECT_EQ(m.poi_sets.size() > 1, several) << fig;
  }
}

// Every POI point is a pattern point, and flipping a POI set changes the
// pattern into one the same mask no longer matches.
TEST(MaskCatalogue, PoiSetsArePatternPoints) {
  for (const auto& m : masks::oriented_masks()) {
    std::map<masks::Offset, bool> sign(m.signs.begin(), m.signs.end());
    EXPECT_EQ(sign.size(), m.signs.size());
    for (const auto& set : m.poi_sets) {
      ASSERT_FALSE(set.empty());
      for (const auto& p : set) EXPECT_EQ(sign.count(p), 1u);
    }
  }
}

// Closed, 2-manifold, oriented, every facet normal a lattice direction.
void expect_valid(const MaskResult& r, const std::string& what) {
  EXPECT_TRUE(check_boundary_edges(r.surface.mesh).passed()) << what;
  EXPECT_TRUE(check_non_manifold_edges(r.surface.mesh).passed()) << what;
  EXPECT_TRUE(check_consistent_orientation(r.surface.mesh).passed()) << what;
  EXPECT_GT(signed_volume(r.surface.mesh), 0) << what;
  EXPECT_EQ(count_unpaired_edges(r.charts.poly), 0u) << what;
  for (const Facet& f : r.charts.poly.facets) {
    ASSERT_GE(f.normal, 0) << what;
    ASSERT_LT(f.normal, 26) << what;
  }
}

// Euler characteristic of a triangle mesh (V - E + F).
long euler(const Mesh& m) {
  std::set<std::pair<int, int>> edges;
  for (const auto& f : m.faces)
    for (int s = 0; s < 3; ++s) edges.insert(std::minmax(f[static_cast<std::size_t>(s)], f[static_cast<std::size_t>((s + 1) % 3)]));
  return static_cast<long>(m.vertices.size()) - static_cast<long>(edges.size()) + static_cast<long>(m.faces.size());
}

TEST(ApplyMasks, RemovesABumpOnAFlatFace) {
  Lattice l = test::block_lattice(9, 2, 6);
  l.inside[l.grid.index(4, 4, 7)] = 1;  // one point on top of the box
  const McSurface before = marching_cubes(l);
  const std::size_t facets_before = extract_charts(before.mesh, before.normals).poly.num_facets();
  const MaskResult r = apply_masks(l, {});
  expect_valid(r, "bump");
  EXPECT_EQ(r.lattice.is_inside(4, 4, 7), false);
  EXPECT_EQ(r.charts.poly.num_facets(), 26u);
  EXPECT_GT(facets_before, 26u);
  EXPECT_GE(r.num_flips, 1u);
}

TEST(ApplyMasks, FillsAPitOnAFlatFace) {
  Lattice l = test::block_lattice(9, 2, 6);
  l.inside[l.grid.index(4, 4, 6)] = 0;  // one point missing from the top layer
  const MaskResult r = apply_masks(l, {});
  expect_valid(r, "pit");
  EXPECT_TRUE(r.lattice.is_inside(4, 4, 6));
  EXPECT_EQ(r.charts.poly.num_facets(), 26u);
}

// A plain box matches no mask of the catalogue: no flip. Single-point
// moves may cut its corners (fewer triangle edges between normals) but never
// add facets.
TEST(ApplyMasks, LeavesABoxAlone) {
  const Lattice l = test::block_lattice(8, 2, 5);
  const MaskResult r = apply_masks(l, {.single_point_moves = false});
  EXPECT_EQ(r.num_flips, 0u);
  EXPECT_EQ(r.lattice.inside, l.inside);
  EXPECT_EQ(r.charts.poly.num_facets(), 26u);
  const MaskResult s = apply_masks(l, {});
  expect_valid(s, "box");
  EXPECT_LE(s.charts.poly.num_facets(), 26u);
}

// Adversarial input: dense random lattices. The stage terminates, keeps the
// surface valid and the topology (Euler characteristic) unchanged, and the
// global cap is honoured.
TEST(ApplyMasks, TerminatesAndKeepsTopologyOnRandomLattices) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 10; ++trial) {
    const int n = 12;
    std::bernoulli_distribution coin(0.35 + 0.05 * trial);
    Lattice l;
    l.grid.size = {n, n, n};
    l.inside.assign(l.grid.num_points(), 0);
    for (int k = 1; k < n - 1; ++k)
      for (int j = 1; j < n - 1; ++j)
        for (int i = 1; i < n - 1; ++i) l.inside[l.grid.index(i, j, k)] = coin(rng);
    const McSurface before = marching_cubes(l);
    const MaskResult r = apply_masks(l, {});
    expect_valid(r, "random " + std::to_string(trial));
    EXPECT_EQ(euler(r.surface.mesh), euler(before.mesh)) << trial;
    // No new self-contact (crossing face diagonals of neighbouring cubes).
    if (check_self_intersections(before.mesh).passed()) {
      EXPECT_TRUE(check_self_intersections(r.surface.mesh).passed()) << trial;
    }
    const MaskResult capped = apply_masks(l, {.max_total_flips = 3});
    EXPECT_LE(capped.num_flips, 3u);
    if (r.num_flips > 3) {
      EXPECT_TRUE(capped.hit_flip_cap);
    }
  }
}

struct ModelCase {
  std::filesystem::path path;
  bool required;
};

TEST(ApplyMasks, RealModelsStayValidAndLoseFacets) {
  const std::vector<ModelCase> models{{test::data_path("bunny_lowres.off"), true},
                                      {test::data_path("spot.obj"), true},
                                      {test::data_path("moai.obj"), true},
                                      {test::data_path("fandisk.obj"), true},
                                      {test::models_path("max_planck.obj"), false}};
  for (const auto& model : models) {
    if (!std::filesystem::exists(model.path)) {
      ASSERT_FALSE(model.required) << model.path;
      continue;
    }
    const Mesh m = read_mesh(model.path);
    const Lattice l = build_lattice(m, {});
    const McSurface s = marching_cubes(l);
    const Charts c = extract_charts(s.mesh, s.normals);
    const MaskResult r = apply_masks(l, {.reference = &m});
    expect_valid(r, model.path.filename().string());
    // Fidelity band: every surface vertex within 1.5 spacings of the input
    // (guaranteed), and the input within 1.5 spacings of the surface (its
    // samples keep a surface vertex in their ball; estimated on samples).
    EXPECT_LE(detail::hausdorff_distance(m, r.surface.mesh, 20000), 1.5 * l.grid.spacing) << model.path;
    EXPECT_LT(r.charts.poly.num_facets(), c.poly.num_facets()) << model.path;
    EXPECT_EQ(euler(r.surface.mesh), euler(s.mesh)) << model.path;
    EXPECT_FALSE(r.hit_flip_cap) << model.path;
    // Fidelity band: every changed point was next to the original surface.
    const GridPoints& g = l.grid;
    std::size_t changed = 0;
    for (int k = 1; k + 1 < g.size[2]; ++k)
      for (int j = 1; j + 1 < g.size[1]; ++j)
        for (int i = 1; i + 1 < g.size[0]; ++i) {
          if (r.lattice.is_inside(i, j, k) == l.is_inside(i, j, k)) continue;
          ++changed;
          const bool v = l.is_inside(i, j, k);
          const bool next_to_surface = l.is_inside(i - 1, j, k) != v || l.is_inside(i + 1, j, k) != v ||
                                       l.is_inside(i, j - 1, k) != v || l.is_inside(i, j + 1, k) != v ||
                                       l.is_inside(i, j, k - 1) != v || l.is_inside(i, j, k + 1) != v;
          EXPECT_TRUE(next_to_surface) << model.path << " " << i << " " << j << " " << k;
        }
    EXPECT_GT(changed, 0u);
  }
}

TEST(ApplyMasks, Deterministic) {
  const Mesh m = read_mesh(test::data_path("fandisk.obj"));
  const Lattice l = build_lattice(m, {});
  const MaskResult a = apply_masks(l, {});
  MaskResult b;
  {
    ThreadLimit one(1);
    b = apply_masks(build_lattice(m, {}), {});
  }
  EXPECT_EQ(a.lattice.inside, b.lattice.inside);
  EXPECT_EQ(a.num_flips, b.num_flips);
  EXPECT_EQ(a.charts.poly.num_facets(), b.charts.poly.num_facets());
}

}  // namespace
}  // namespace subfab
