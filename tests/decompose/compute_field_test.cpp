// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/decompose/compute_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "subfab/geometry/classify_grid_points.h"
#include "geometry/exact_normal_signs.h"
#include "decompose/mark_triangle_cells.h"
#include "geometry/triangle_meets_closed_box.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/mesh/read_mesh.h"
#include "support/box_shapes.h"
#include "support/test_support.h"

namespace subfab {
namespace {

//! Closed, outward-oriented axis-aligned box [lo, hi] (12 triangles).
Mesh box_mesh(const Vec3& lo, const Vec3& hi) { return test::make_box_mesh(lo, hi); }

//! A grid with the given origin, spacing and size.
GridGeometry hand_grid(const Vec3& origin, double spacing, std::array<int, 3> n) {
  GridGeometry g;
  g.origin = origin;
  g.spacing = spacing;
  g.num_points = n;
  return g;
}

//! Does the closed cell with lowest corner (i, j, k) meet the closed box [lo, hi]?
bool cell_meets(const GridGeometry& g, int i, int j, int k, const Vec3& lo, const Vec3& hi) {
  const std::array<int, 3> c{i, j, k};
  for (int d = 0; d < 3; ++d)
    if (g.coordinate(d, c[static_cast<std::size_t>(d)] + 1) < lo[d] || g.coordinate(d, c[static_cast<std::size_t>(d)]) > hi[d])
      return false;
  return true;
}

//! Expected field of an axis-aligned box solid, from the six faces as
//! degenerate boxes (independent of the implementation's triangle tests).
std::vector<FieldValue> expected_box_field(const GridGeometry& g, const Vec3& lo, const Vec3& hi, Axis axis) {
  std::vector<FieldValue> out(g.num_total_points(), FieldValue::Free);
  const int dim = axis_dimension(axis);
  for (int face = 0; face < 6; ++face) {
    const int d = face / 2;
    const bool upper = face % 2 == 1;  // face at hi[d] with outward normal +d
    Vec3 flo = lo, fhi = hi;
    flo[d] = fhi[d] = upper ? hi[d] : lo[d];
    const int normal_sign = upper ? 1 : -1;
    const bool away = d == dim && normal_sign != axis_sign(axis);
    for (int k = 0; k + 1 < g.num_points[2]; ++k)
      for (int j = 0; j + 1 < g.num_points[1]; ++j)
        for (int i = 0; i + 1 < g.num_points[0]; ++i) {
          if (!cell_meets(g, i, j, k, flo, fhi)) continue;
          for (int c = 0; c < 8; ++c) {
            auto& v = out[g.index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))];
            if (away)
              v = FieldValue::Forbidden;
            else if (v == FieldValue::Free)
              v = FieldValue::Good;
          }
        }
  }
  return out;
}

std::int64_t brute_count(const HeightField& f, const std::array<int, 3>& lo, const std::array<int, 3>& hi, FieldValue what) {
  std::int64_t n = 0;
  for (int k = std::max(lo[2], 0); k <= std::min(hi[2], f.grid.num_points[2] - 1); ++k)
    for (int j = std::max(lo[1], 0); j <= std::min(hi[1], f.grid.num_points[1] - 1); ++j)
      for (int i = std::max(lo[0], 0); i <= std::min(hi[0], f.grid.num_points[0] - 1); ++i)
        n += f.values[f.grid.index(i, j, k)] == what;
  return n;
}

TEST(MakeGrid, PadsTheBoundingBoxByOneCell) {
  const Mesh mesh = read_mesh(test::data_path("spot.obj"));
  const GridGeometry g = make_grid(mesh, 1.0);
  EXPECT_DOUBLE_EQ(g.spacing, average_edge_length(mesh));
  const BoundingBox box = bounding_box(mesh);
  for (int c = 0; c < 3; ++c) {
    EXPECT_LE(g.coordinate(c, 0), box.min[c] - g.spacing * (1 - 1e-12));
    EXPECT_GE(g.coordinate(c, g.num_points[static_cast<std::size_t>(c)] - 1), box.max[c] + g.spacing);
    EXPECT_LT(g.coordinate(c, g.num_points[static_cast<std::size_t>(c)] - 2), box.max[c] + g.spacing * 1.5);
  }
  EXPECT_EQ(g.index(1, 2, 3), 1u + static_cast<std::size_t>(g.num_points[0]) * (2u + static_cast<std::size_t>(g.num_points[1]) * 3u));
  const GridGeometry coarse = make_grid(mesh, 2.0);
  EXPECT_DOUBLE_EQ(coarse.spacing, 2 * g.spacing);
  EXPECT_THROW(make_grid(mesh, 0.0), InvalidArgumentError);
  EXPECT_THROW(make_grid(mesh, 1e-9), InvalidArgumentError);  // far too many points
  EXPECT_THROW(make_grid(Mesh{}, 1.0), InvalidMeshError);
}

// An axis-aligned cube: for direction +z the only triangles facing away are
// the two of the bottom face (n = -z); the side faces (n.z == 0) face +z. So
// the Forbidden points are exactly the corners of the cells the bottom face
// touches, for each of the six directions its opposite face.
TEST(ComputeFields, CubeForbiddenOnlyAtTheOppositeFace) {
  const Vec3 lo(0, 0, 0), hi(1, 1, 1);
  const Mesh cube = box_mesh(lo, hi);
  // Faces on grid planes (spacing 0.25, origin -0.5) and off them (spacing 0.3).
  for (const GridGeometry& g : {hand_grid(Vec3::Constant(-0.5), 0.25, {9, 9, 9}),
                                hand_grid(Vec3(-0.55, -0.45, -0.61), 0.3, {8, 7, 8})}) {
    const auto fields = compute_fields(cube, g, {});
    for (Axis a : kAllAxes) {
      const HeightField& f = fields[static_cast<std::size_t>(axis_index(a))];
      EXPECT_EQ(f.axis, a);
      const auto expected = expected_box_field(g, lo, hi, a);
      ASSERT_EQ(f.values.size(), expected.size());
      std::int64_t forbidden = 0;
      for (std::size_t p = 0; p < expected.size(); ++p) {
        EXPECT_EQ(f.values[p], expected[p]) << axis_name(a) << " point " << p;
        forbidden += f.values[p] == FieldValue::Forbidden;
      }
      EXPECT_GT(forbidden, 0);
      // The Forbidden points hug the opposite face: within one cell of it.
      const int d = axis_dimension(a);
      const double face = axis_sign(a) > 0 ? lo[d] : hi[d];
      for (int k = 0; k < g.num_points[2]; ++k) {
        for (int j = 0; j < g.num_points[1]; ++j) {
          for (int i = 0; i < g.num_points[0]; ++i) {
            if (f.values[g.index(i, j, k)] == FieldValue::Forbidden) {
              EXPECT_LE(std::abs(g.point(i, j, k)[d] - face), 2 * g.spacing);
            }
          }
        }
      }
    }
    // With faces on grid planes, the bottom face touches two cell layers: three point layers.
    if (g.spacing == 0.25) {
      const HeightField& up = fields[static_cast<std::size_t>(axis_index(Axis::PosZ))];
      EXPECT_EQ(up.values[g.index(4, 4, 1)], FieldValue::Forbidden);  // z = -0.25
      EXPECT_EQ(up.values[g.index(4, 4, 2)], FieldValue::Forbidden);  // z = 0
      EXPECT_EQ(up.values[g.index(4, 4, 3)], FieldValue::Forbidden);  // z = 0.25
      EXPECT_EQ(up.values[g.index(4, 4, 4)], FieldValue::Free);       // centre, far from every face
      EXPECT_EQ(up.values[g.index(4, 4, 6)], FieldValue::Good);       // z = 1
    }
  }
}

// Every triangle marks the cell around its centroid: the corners are
// Forbidden for the directions it faces away from, and not Free for the others.
TEST(ComputeFields, RealModelTrianglesMarkTheCellAroundThem) {
  const Mesh mesh = read_mesh(test::data_path("bunny_lowres.off"));
  const auto fields = compute_fields(mesh, {});
  const GridGeometry& g = fields[0].grid;
  std::size_t num_away = 0;
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    const Vec3 a = mesh.vertices[static_cast<std::size_t>(t[0])], b = mesh.vertices[static_cast<std::size_t>(t[1])],
               c = mesh.vertices[static_cast<std::size_t>(t[2])];
    const Vec3 centroid = (a + b + c) / 3.0;
    std::array<int, 3> cell{};
    for (int d = 0; d < 3; ++d) cell[static_cast<std::size_t>(d)] = g.index_at_or_below(d, centroid[d]);
    const auto signs = detail::exact_normal_signs(a, b, c);
    for (Axis axis : kAllAxes) {
      const bool away = signs[static_cast<std::size_t>(axis_dimension(axis))] * axis_sign(axis) < 0;
      num_away += away;
      for (int corner = 0; corner < 8; ++corner) {
        const FieldValue v = fields[static_cast<std::size_t>(axis_index(axis))]
                                 .values[g.index(cell[0] + (corner & 1), cell[1] + ((corner >> 1) & 1), cell[2] + ((corner >> 2) & 1))];
        if (away)
          ASSERT_EQ(v, FieldValue::Forbidden) << "face " << f << " " << axis_name(axis);
        else
          ASSERT_NE(v, FieldValue::Free) << "face " << f << " " << axis_name(axis);
      }
    }
  }
  EXPECT_GT(num_away, mesh.num_faces());
}

// The guarantee box growth can rely on: a box spanning grid points [lo, hi]
// with no Forbidden point meets no triangle facing away from the direction,
// not even on its boundary (checked against every triangle, exactly).
TEST(ComputeFields, NoForbiddenPointMeansNoFacingAwayTriangleInTheBox) {
  const Mesh mesh = read_mesh(test::data_path("bunny_lowres.off"));
  const auto fields = compute_fields(mesh, {.grid_factor = 2.0});
  const GridGeometry& g = fields[0].grid;
  std::mt19937 rng(7);
  int num_clear = 0;
  for (int trial = 0; trial < 3000 && num_clear < 60; ++trial) {
    const Axis axis = kAllAxes[static_cast<std::size_t>(trial % 6)];
    const HeightField& field = fields[static_cast<std::size_t>(axis_index(axis))];
    std::array<int, 3> lo{}, hi{};
    for (std::size_t c = 0; c < 3; ++c) {
      std::uniform_int_distribution<int> start(0, g.num_points[c] - 2), length(1, 6);
      lo[c] = start(rng);
      hi[c] = std::min(lo[c] + length(rng), g.num_points[c] - 1);
    }
    if (field.count_forbidden(lo, hi) != 0 || field.count_good(lo, hi) == 0) continue;
    ++num_clear;
    const Box3 box{g.point(lo[0], lo[1], lo[2]), g.point(hi[0], hi[1], hi[2])};
    const int d = axis_dimension(axis);
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
      const auto& t = mesh.faces[f];
      const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
      const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
      const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
      if (detail::exact_normal_signs(a, b, c)[static_cast<std::size_t>(d)] * axis_sign(axis) >= 0) continue;
      ASSERT_FALSE(detail::triangle_meets_closed_box(a, b, c, box)) << "face " << f << " " << axis_name(axis);
    }
  }
  EXPECT_GE(num_clear, 60);
}

TEST(MarkTriangleCells, DegenerateTriangleMarksTheCellsOfItsSegment) {
  Mesh sliver;
  sliver.vertices = {Vec3(0.1, 0.1, 0.1), Vec3(0.9, 0.1, 0.1), Vec3(0.5, 0.1, 0.1)};
  sliver.faces = {{0, 1, 2}};
  const GridGeometry g = hand_grid(Vec3::Zero(), 0.25, {5, 5, 5});
  const auto flags = detail::mark_triangle_cells(sliver, g);
  const std::uint16_t all_zero = detail::cell_flag_zero(0) | detail::cell_flag_zero(1) | detail::cell_flag_zero(2);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        EXPECT_EQ(flags[detail::cell_index(g, i, j, k)], (j == 0 && k == 0) ? all_zero : 0) << i << " " << j << " " << k;
}

TEST(ComputeFields, PointFarOutsideIsFree) {
  const Mesh cube = box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const GridGeometry g = hand_grid(Vec3::Constant(-2), 0.5, {11, 11, 11});
  const auto fields = compute_fields(cube, g, {.max_height = 0.1});
  for (const HeightField& f : fields) {
    EXPECT_EQ(f.values[g.index(0, 0, 0)], FieldValue::Free);
    EXPECT_EQ(f.values[g.index(10, 10, 10)], FieldValue::Free);
    EXPECT_EQ(f.values[g.index(0, 5, 10)], FieldValue::Free);
  }
}

TEST(HeightField, PrefixCountsEqualBruteForce) {
  const Mesh mesh = read_mesh(test::data_path("bunny_lowres.off"));
  const auto fields = compute_fields(mesh, {.grid_factor = 2.0, .max_height = 0.02});
  std::mt19937 rng(12345);
  for (const HeightField& f : fields) {
    std::int64_t total_forbidden = 0, total_good = 0;
    for (FieldValue v : f.values) {
      total_forbidden += v == FieldValue::Forbidden;
      total_good += v == FieldValue::Good;
    }
    EXPECT_GT(total_forbidden, 0);
    EXPECT_GT(total_good, 0);
    const std::array<int, 3> all_lo{0, 0, 0};
    const std::array<int, 3> all_hi{f.grid.num_points[0] - 1, f.grid.num_points[1] - 1, f.grid.num_points[2] - 1};
    EXPECT_EQ(f.count_forbidden(all_lo, all_hi), total_forbidden);
    EXPECT_EQ(f.count_good(all_lo, all_hi), total_good);
    for (int trial = 0; trial < 200; ++trial) {
      std::array<int, 3> lo{}, hi{};
      for (std::size_t c = 0; c < 3; ++c) {
        std::uniform_int_distribution<int> pick(-2, f.grid.num_points[c] + 1);
        lo[c] = pick(rng);
        hi[c] = pick(rng);
        if (trial % 2 == 0 && lo[c] > hi[c]) std::swap(lo[c], hi[c]);
      }
      EXPECT_EQ(f.count_forbidden(lo, hi), brute_count(f, lo, hi, FieldValue::Forbidden));
      EXPECT_EQ(f.count_good(lo, hi), brute_count(f, lo, hi, FieldValue::Good));
    }
  }
}

// A tall box 1 x 1 x 4 with max_height = 0.3 x 4 = 1.2: along +-z the points
// inside deeper than 1.2 from the exit face are Forbidden; across x and y the
// box is thinner than the limit, so nothing is too deep there.
TEST(ComputeFields, HeightLimitForbidsOnlyDeepPoints) {
  const Vec3 lo(0, 0, 0), hi(1, 1, 4);
  const Mesh box = box_mesh(lo, hi);
  const GridGeometry g = hand_grid(Vec3(-0.37, -0.41, -0.33), 0.2, {9, 9, 25});
  const double max_height = 0.3 * 4;
  const auto fields = compute_fields(box, g, {.max_height = max_height});
  const auto inside = classify_grid_points(box, GridPoints{.origin = g.origin, .spacing = g.spacing, .size = g.num_points});
  for (Axis a : kAllAxes) {
    const HeightField& f = fields[static_cast<std::size_t>(axis_index(a))];
    const auto surface_only = expected_box_field(g, lo, hi, a);
    const int d = axis_dimension(a);
    std::int64_t num_deep = 0;
    for (int k = 0; k < g.num_points[2]; ++k)
      for (int j = 0; j < g.num_points[1]; ++j)
        for (int i = 0; i < g.num_points[0]; ++i) {
          const std::size_t p = g.index(i, j, k);
          const Vec3 x = g.point(i, j, k);
          const double exit = axis_sign(a) > 0 ? hi[d] - x[d] : x[d] - lo[d];
          const bool deep = inside[p] > 0 && exit > max_height;
          const FieldValue expected = deep ? FieldValue::Forbidden : surface_only[p];
          EXPECT_EQ(f.values[p], expected) << axis_name(a) << " at " << x.transpose();
          num_deep += deep && surface_only[p] != FieldValue::Forbidden;
        }
    if (d == 2)
      EXPECT_GT(num_deep, 0) << axis_name(a);
    else
      EXPECT_EQ(num_deep, 0) << axis_name(a);
  }
}

TEST(ComputeFields, IdenticalWhateverTheThreadCount) {
  const Mesh mesh = read_mesh(test::data_path("bunny_lowres.off"));
  const FieldOptions options{.grid_factor = 1.0, .max_height = 0.03};
  const auto parallel = compute_fields(mesh, options);
  std::array<HeightField, 6> serial;
  {
    ThreadLimit one(1);
    serial = compute_fields(mesh, options);
  }
  for (std::size_t a = 0; a < 6; ++a) {
    EXPECT_EQ(serial[a].values, parallel[a].values);
    EXPECT_EQ(serial[a].prefix_forbidden, parallel[a].prefix_forbidden);
    EXPECT_EQ(serial[a].prefix_good, parallel[a].prefix_good);
  }
}

TEST(ComputeFields, RejectsBadOptions) {
  const Mesh cube = box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
  EXPECT_THROW(compute_fields(cube, {.max_height = 0.0}), InvalidArgumentError);
  EXPECT_THROW(compute_fields(cube, {.max_height = std::nan("")}), InvalidArgumentError);
  EXPECT_THROW(compute_fields(cube, {.grid_factor = -1.0}), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
