// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/geometry/classify_grid_points.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <gtest/gtest.h>

#include <cmath>

#include "support/test_shapes.h"
#include "subfab/core/error.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

GridPoints hand_grid(const Vec3& origin, double spacing, std::array<int, 3> n) {
  return GridPoints{.origin = origin, .spacing = spacing, .size = n};
}

//! A grid over the mesh's bounding box, padded by one point, with `n` points
//! along the longest side.
GridPoints grid_over(const Mesh& mesh, int n) {
  const BoundingBox b = bounding_box(mesh);
  const double spacing = (b.max - b.min).maxCoeff() / (n - 1);
  GridPoints g{.origin = b.min - Vec3::Constant(spacing), .spacing = spacing};
  for (int d = 0; d < 3; ++d)
    g.size[static_cast<std::size_t>(d)] = static_cast<int>(std::ceil((b.max[d] - b.min[d]) / spacing)) + 3;
  return g;
}

// Rule: p is classified as p + (e, e^2, e^3); for the cube [0, 1]^3 that makes
// the inside exactly the half-open box [0, 1)^3 for grid points, including
// grid points on faces, edges and corners.
TEST(ClassifyGridPoints, CubeIsHalfOpenOnItsFaces) {
  const Mesh cube = test::cube();
  for (const GridPoints& g : {hand_grid(Vec3::Constant(-0.5), 0.25, {9, 9, 9}),
                              hand_grid(Vec3(-0.55, -0.45, -0.61), 0.3, {8, 7, 8})}) {
    const auto winding = classify_grid_points(cube, g);
    std::size_t num_inside = 0;
    for (int k = 0; k < g.size[2]; ++k)
      for (int j = 0; j < g.size[1]; ++j)
        for (int i = 0; i < g.size[0]; ++i) {
          const Vec3 p = g.point(i, j, k);
          const bool expected = (p.array() >= 0).all() && (p.array() < 1).all();
          EXPECT_EQ(winding[g.index(i, j, k)], expected ? 1 : 0) << p.transpose();
          num_inside += expected;
        }
    EXPECT_GT(num_inside, 0u);
  }
}

// An inward-oriented cube has winding -1 inside.
TEST(ClassifyGridPoints, InwardOrientationGivesMinusOne) {
  Mesh cube = test::cube();
  for (auto& f : cube.faces) std::swap(f[1], f[2]);
  const GridPoints g = hand_grid(Vec3::Constant(0.1), 0.2, {5, 5, 5});
  for (int w : classify_grid_points(cube, g)) EXPECT_EQ(w, -1);
}

// Independent exact check (CGAL Side_of_triangle_mesh on an exact kernel) on
// every grid point not lying on the surface.
TEST(ClassifyGridPoints, AgreesWithExactSideOfTriangleMesh) {
  using K = CGAL::Exact_predicates_exact_constructions_kernel;
  using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
  for (const char* name : {"spot.obj", "bunny_lowres.off"}) {
    const Mesh mesh = read_mesh(test::data_path(name));
    SurfaceMesh sm;
    std::vector<SurfaceMesh::Vertex_index> vs;
    for (const Vec3& p : mesh.vertices) vs.push_back(sm.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
    for (const auto& t : mesh.faces)
      sm.add_face(vs[static_cast<std::size_t>(t[0])], vs[static_cast<std::size_t>(t[1])], vs[static_cast<std::size_t>(t[2])]);
    CGAL::Side_of_triangle_mesh<SurfaceMesh, K> side(sm);
    const GridPoints g = grid_over(mesh, 40);
    const auto winding = classify_grid_points(mesh, g);
    std::size_t num_inside = 0, num_checked = 0;
    for (int k = 0; k < g.size[2]; ++k)
      for (int j = 0; j < g.size[1]; ++j)
        for (int i = 0; i < g.size[0]; ++i) {
          const Vec3 p = g.point(i, j, k);
          const auto s = side(K::Point_3(p.x(), p.y(), p.z()));
          if (s == CGAL::ON_BOUNDARY) continue;
          ++num_checked;
          num_inside += s == CGAL::ON_BOUNDED_SIDE;
          ASSERT_EQ(winding[g.index(i, j, k)], s == CGAL::ON_BOUNDED_SIDE ? 1 : 0) << name << " at " << p.transpose();
        }
    EXPECT_GT(num_inside, 100u) << name;
    EXPECT_GT(num_checked, 1000u) << name;
  }
}

// Along every dimension, a line through the open square of the cube's
// cross-section crosses it at 0 and 1; lines on the square's boundary follow
// the half-open rule; lines outside cross nothing.
TEST(ComputeLineCrossings, CubeAlongEveryDimension) {
  const Mesh cube = test::cube();
  const GridPoints g = hand_grid(Vec3::Constant(-0.5), 0.25, {9, 9, 9});
  for (int dim = 0; dim < 3; ++dim) {
    const LineCrossings lines = compute_line_crossings(cube, g, dim);
    const int u = (dim + 1) % 3, v = (dim + 2) % 3;
    ASSERT_EQ(lines.dim, dim);
    ASSERT_EQ(lines.num_lines[0], g.size[static_cast<std::size_t>(u)]);
    ASSERT_EQ(lines.offsets.size(), static_cast<std::size_t>(9 * 9 + 1));
    std::size_t num_crossed_lines = 0;
    for (int b = 0; b < 9; ++b)
      for (int a = 0; a < 9; ++a) {
        const std::size_t l = static_cast<std::size_t>(a + 9 * b);
        const double cu = g.coordinate(u, a), cv = g.coordinate(v, b);
        const bool through = cu >= 0 && cu < 1 && cv >= 0 && cv < 1;
        const std::size_t n = lines.offsets[l + 1] - lines.offsets[l];
        ASSERT_EQ(n, through ? 2u : 0u) << "dim " << dim << " line " << cu << ", " << cv;
        if (!through) continue;
        ++num_crossed_lines;
        EXPECT_EQ(lines.positions[lines.offsets[l]], 0.0);
        EXPECT_EQ(lines.positions[lines.offsets[l] + 1], 1.0);
      }
    EXPECT_EQ(num_crossed_lines, 16u);  // 4 x 4 lines at -0.5 + 0.25 k in [0, 1)
  }
}

// On a closed mesh, every line crosses the surface an even number of times
// and, for z-lines, the parity between consecutive crossings matches the
// classification of the grid points.
TEST(ComputeLineCrossings, EvenCountsAndConsistentWithClassification) {
  const Mesh mesh = read_mesh(test::data_path("bunny_lowres.off"));
  const GridPoints g = grid_over(mesh, 30);
  const auto winding = classify_grid_points(mesh, g);
  for (int dim = 0; dim < 3; ++dim) {
    const LineCrossings lines = compute_line_crossings(mesh, g, dim);
    std::size_t total = 0;
    for (std::size_t l = 0; l + 1 < lines.offsets.size(); ++l) {
      const std::size_t n = lines.offsets[l + 1] - lines.offsets[l];
      EXPECT_EQ(n % 2, 0u) << "dim " << dim << " line " << l;
      total += n;
      if (dim != 2 || n == 0) continue;
      const int i = static_cast<int>(l % static_cast<std::size_t>(g.size[0]));
      const int j = static_cast<int>(l / static_cast<std::size_t>(g.size[0]));
      for (int k = 0; k < g.size[2]; ++k) {
        const double z = g.coordinate(2, k);
        std::size_t below = 0;
        for (std::size_t c = lines.offsets[l]; c < lines.offsets[l + 1]; ++c) below += lines.positions[c] < z;
        // Points within rounding of a crossing are skipped (positions are rounded).
        bool near = false;
        for (std::size_t c = lines.offsets[l]; c < lines.offsets[l + 1]; ++c)
          near = near || std::abs(lines.positions[c] - z) < 1e-9;
        if (!near) {
          EXPECT_EQ(winding[g.index(i, j, k)], static_cast<int>(below % 2)) << i << " " << j << " " << k;
        }
      }
    }
    EXPECT_GT(total, 100u);
  }
}

TEST(ClassifyGridPoints, RejectsEmptyGridAndBadDimension) {
  const Mesh cube = test::cube();
  EXPECT_THROW(classify_grid_points(cube, hand_grid(Vec3::Zero(), 0.1, {0, 3, 3})), InvalidArgumentError);
  EXPECT_THROW(classify_grid_points(cube, hand_grid(Vec3::Zero(), 0.0, {3, 3, 3})), InvalidArgumentError);
  EXPECT_THROW(compute_line_crossings(cube, hand_grid(Vec3::Zero(), 0.1, {3, 3, 3}), 3), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
