// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/fidelity/restore_details.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/exact_normal_signs.h"
#include "subfab/checks/require_closed_solid.h"
#include "subfab/core/error.h"
#include "subfab/fidelity/smooth_for_decomposition.h"
#include "support/smooth_test_shapes.h"

namespace subfab {
namespace {

using test::bumped_cube;

//! Faces of the top (every corner above z = 0.9) whose exact normal has a
//! negative z component.
int num_down_faces(const Mesh& m) {
  int count = 0;
  for (const Triangle& t : m.faces) {
    const Vec3& a = m.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = m.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = m.vertices[static_cast<std::size_t>(t[2])];
    if (std::min({a.z(), b.z(), c.z()}) > 0.9 && detail::exact_normal_signs(a, b, c)[2] < 0) ++count;
  }
  return count;
}

double max_vertex_distance(const Mesh& a, const Mesh& b) {
  double d = 0;
  for (std::size_t v = 0; v < a.vertices.size(); ++v) d = std::max(d, (a.vertices[v] - b.vertices[v]).norm());
  return d;
}

HeightBox box_along_z(const Vec3& lo, const Vec3& hi) { return HeightBox{.box = {lo, hi}, .axis = Axis::PosZ}; }

TEST(RestoreDetails, UnconstrainedBumpComesBackExactly) {
  const Mesh original = bumped_cube(10, 0.2);
  const SmoothResult smoothed = smooth_for_decomposition(original, {.num_passes = 60, .max_deviation = 0.05});
  ASSERT_GT(max_vertex_distance(original, smoothed.mesh), 0.02);  // the bump was flattened
  // One box around everything, milled from +z: every face of the bump faces +z.
  const std::vector<HeightBox> boxes = {box_along_z(Vec3(-1, -1, -1), Vec3(2, 2, 2))};
  const RestoreDetailsResult r = restore_details(original, smoothed.mesh, boxes);
  EXPECT_EQ(r.mesh.faces, original.faces);
  EXPECT_LT(max_vertex_distance(original, r.mesh), 1e-9);
  EXPECT_EQ(r.report.num_held_back, 0);
  EXPECT_EQ(r.report.num_outside_boxes, 0);
  EXPECT_EQ(r.report.num_restored, static_cast<int>(original.vertices.size()));
  for (int region : r.region) EXPECT_EQ(region, 0);
}

TEST(RestoreDetailsBox, VerticesStayInTheirBoxAndTheRestComesBack) {
  const Mesh original = bumped_cube(10, 0.2);
  const SmoothResult smoothed = smooth_for_decomposition(original, {.num_passes = 60, .max_deviation = 0.05});
  double top = 0;
  for (const Vec3& p : smoothed.mesh.vertices) top = std::max(top, p.z());
  ASSERT_LT(top, 1.18);
  // The box stops at the smoothed bump's top: the bump cannot come back whole.
  const std::vector<HeightBox> boxes = {box_along_z(Vec3(-1, -1, -1), Vec3(2, 2, top))};
  const RestoreDetailsResult r = restore_details(original, smoothed.mesh, boxes);
  for (const Vec3& p : r.mesh.vertices) EXPECT_LE(p.z(), top);
  EXPECT_GT(r.report.num_held_on_box, 0);
  EXPECT_NEAR(max_vertex_distance(original, r.mesh), 1.2 - top, 0.02);  // the peak is cut at the box
  EXPECT_LT(r.report.mean_displacement, 0.05 * r.report.mean_displacement_smoothed);
  // Far from the bump the surface is back (the corners of the top face).
  for (std::size_t v = 0; v < original.vertices.size(); ++v) {
    if (original.vertices[v].z() == 1.0 && (original.vertices[v] - Vec3(0.5, 0.5, 1)).norm() > 0.45) {
      EXPECT_LT((r.mesh.vertices[v] - original.vertices[v]).norm(), 1e-4);
    }
  }
  Mesh check = r.mesh;
  EXPECT_NO_THROW(require_closed_solid(check));
}

TEST(RestoreDetails, NoFaceTurnsAwayFromItsDirection) {
  const Mesh original = bumped_cube(14, 0.25, 0.2);
  ASSERT_GT(num_down_faces(original), 0);  // the leaning bump overhangs: not a height field along +z
  const SmoothResult smoothed = smooth_for_decomposition(original, {.num_passes = 100, .max_deviation = 0.1});
  ASSERT_EQ(num_down_faces(smoothed.mesh), 0);  // smoothing removed the undercut
  const std::vector<HeightBox> boxes = {box_along_z(Vec3(-1, -1, 0), Vec3(2, 2, 2))};
  const RestoreDetailsResult r = restore_details(original, smoothed.mesh, boxes);
  EXPECT_EQ(num_down_faces(r.mesh), 0);  // exact: no face of the restored bump faces down
  EXPECT_GT(r.report.num_face_failures, 0);
  EXPECT_GT(r.report.num_held_back, 0);
  EXPECT_LT(r.report.mean_displacement, 0.6 * r.report.mean_displacement_smoothed);  // much of the detail is back
  Mesh check = r.mesh;
  EXPECT_NO_THROW(require_closed_solid(check));
}

TEST(RestoreDetails, HeldVerticesStayAtTheirSmoothedPositions) {
  const Mesh original = bumped_cube(8, 0.2);
  const SmoothResult smoothed = smooth_for_decomposition(original, {.num_passes = 40, .max_deviation = 0.05});
  const std::vector<HeightBox> boxes = {box_along_z(Vec3(-1, -1, -1), Vec3(2, 2, 2))};
  std::vector<int> held;
  for (std::size_t v = 0; v < original.vertices.size(); ++v)
    if (smoothed.mesh.vertices[v] != original.vertices[v]) held.push_back(static_cast<int>(v));
  ASSERT_FALSE(held.empty());
  const RestoreDetailsResult r = restore_details(original, smoothed.mesh, boxes, {.held = &held});
  for (int v : held) EXPECT_EQ(r.mesh.vertices[static_cast<std::size_t>(v)], smoothed.mesh.vertices[static_cast<std::size_t>(v)]);
}

TEST(RestoreDetails, RejectsMeshesThatDoNotCorrespond) {
  const Mesh a = bumped_cube(4, 0.1), b = bumped_cube(5, 0.1);
  const std::vector<HeightBox> boxes = {box_along_z(Vec3(-1, -1, -1), Vec3(2, 2, 2))};
  EXPECT_THROW(restore_details(a, b, boxes), InvalidArgumentError);
  EXPECT_THROW(restore_details(a, a, boxes, {.anchor_weight = 0}), InvalidArgumentError);
}

}  // namespace
}  // namespace subfab
