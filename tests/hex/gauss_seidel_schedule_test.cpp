// SPDX-License-Identifier: GPL-3.0-or-later
#include "hex/gauss_seidel_schedule.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "hex/hex_corners.h"
#include "hex/hex_topology.h"
#include "subfab/core/parallel.h"
#include "subfab/hex/optimize_hex_mesh.h"
#include "subfab/hex/raise_min_scaled_jacobian.h"
#include "subfab/hex/scaled_jacobian.h"
#include "support/hex_test_shapes.h"
#include "support/test_shapes.h"

namespace subfab {
namespace {

std::size_t idx(int v) { return static_cast<std::size_t>(v); }

//! The n^3 grid of [0,n]^3 with every vertex moved by a fixed pseudo-random
//! offset (interior ones up to 0.4, boundary ones within their face), so
//! that many elements need work and the waves are wide.
HexMesh jittered_grid(int n) {
  HexMesh m = test::hex_grid(n, n, n);
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    Vec3& p = m.vertices[v];
    for (int a = 0; a < 3; ++a) {
      if (p[a] <= 0 || p[a] >= n) continue;  // stays on its face of the cube
      p[a] += 0.4 * std::sin(1.7 * static_cast<double>(v) + 2.3 * a);
    }
  }
  return m;
}

TEST(GaussSeidelSchedule, WavesKeepTheOrderOfVerticesSharingAHexahedron) {
  const HexMesh m = test::hex_grid(4, 4, 4);
  const detail::HexTopology topo = detail::hex_topology(m);
  std::vector<std::size_t> order;
  for (std::size_t v = 0; v < m.vertices.size(); v += 2) order.push_back(v);  // every other vertex
  for (std::size_t v = 1; v < m.vertices.size(); v += 2) order.push_back(v);  // then the rest
  const auto waves = detail::gauss_seidel_schedule(m, topo, order);
  std::vector<std::size_t> wave_of(m.vertices.size()), position(m.vertices.size());
  std::size_t count = 0;
  for (std::size_t w = 0; w < waves.size(); ++w)
    for (std::size_t v : waves[w]) wave_of[v] = w, ++count;
  for (std::size_t i = 0; i < order.size(); ++i) position[order[i]] = i;
  EXPECT_EQ(count, order.size());
  EXPECT_LT(waves.size(), order.size() / 4);  // real parallelism
  // two vertices of one hexahedron: the earlier one in `order` is in an earlier wave
  for (const Hex& h : m.hexes)
    for (int a : h)
      for (int b : h)
        if (a != b && position[idx(a)] < position[idx(b)]) {
          EXPECT_LT(wave_of[idx(a)], wave_of[idx(b)]);
        }
}

TEST(GaussSeidelSchedule, StarValuesAreTheCornerDeterminantsBitForBit) {
  HexMesh m = jittered_grid(3);
  const detail::HexTopology topo = detail::hex_topology(m);
  const std::size_t v = 1 + 4 * 1 + 16 * 2;  // interior vertex (1,1,2)
  const detail::CornerCache cache = detail::corner_cache(m);
  const detail::VertexStar st = detail::vertex_star(m, topo.vertex_hexes[v], v, 10.0, &cache);
  m.vertices[v] += Vec3(0.11, -0.07, 0.05);
  detail::evaluate_star(m, st);
  const std::vector<double> sj = scaled_jacobians(m);
  for (std::size_t j = 0; j < topo.vertex_hexes[v].size(); ++j) {
    const int h = topo.vertex_hexes[v][j];
    EXPECT_EQ(detail::star_hex_quality(st, j), sj[idx(h)]);  // exact, not near
    for (int c = 0; c < 8; ++c)
      if (const int s = st.slot[8 * j + idx(c)]; s >= 0) {
        EXPECT_EQ(st.values[idx(s)], detail::corner_determinant(m, {h, c}));
      }
  }
}

// Issue 14: the optimisers' sweeps run in waves in parallel; the result
// must not depend on the number of threads (bit for bit).
TEST(GaussSeidelSchedule, OptimisersGiveTheSameMeshWhateverTheThreadCount) {
  const int n = 6;
  const Mesh surface = test::cube(Vec3::Zero(), n);
  std::vector<std::vector<Vec3>> results;
  for (std::size_t threads : {1, 2, 4}) {
    const ThreadLimit limit(threads);
    HexMesh m = jittered_grid(n);
    const OptimizeHexMeshReport r = optimize_hex_mesh(m, surface, {.passes = 8});
    EXPECT_EQ(r.num_inverted, 0u);
    raise_min_scaled_jacobian(m, surface, {.sweeps = 3, .quality_sweeps = 1});
    results.push_back(m.vertices);
  }
  const HexMesh start = jittered_grid(n);
  EXPECT_NE(results[0], start.vertices);  // it did move vertices
  for (std::size_t i = 1; i < results.size(); ++i)
    for (std::size_t v = 0; v < results[0].size(); ++v)
      ASSERT_EQ(results[i][v], results[0][v]) << "vertex " << v << ", run " << i;
}

}  // namespace
}  // namespace subfab
