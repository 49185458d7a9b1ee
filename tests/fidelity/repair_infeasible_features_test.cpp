// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/fidelity/repair_infeasible_features.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/box_shapes.h"
#include "subfab/checks/require_closed_solid.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/decompose.h"
#include "subfab/fidelity/find_infeasible_features.h"
#include "subfab/decompose/grow_boxes.h"
#include "subfab/decompose/orient_mesh.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

//! A thin wedge (prism over a triangle with a 30-degree apex) whose sharp
//! edge runs along (1, 1, 1): the two faces at that edge have normals with
//! opposite signs in every coordinate, so no axis sees both sides.
//! Vertices 0 and 3 are the ends of the sharp edge.
Mesh make_oblique_wedge(double apex_degrees = 30.0) {
  const Vec3 e = Vec3(1, 1, 1).normalized();
  const Vec3 w = Vec3(1, 1, -2).normalized();
  const Vec3 u = Vec3(1, -1, 0).normalized();  // u, w, e orthonormal
  const double half = apex_degrees * M_PI / 360.0, length = 1.0, height = 1.5;
  const Vec3 a = Vec3(0.1, 0.2, 0.3);
  const Vec3 b = a + length * (std::cos(half) * u + std::sin(half) * w);
  const Vec3 c = a + length * (std::cos(half) * u - std::sin(half) * w);
  Mesh m;
  m.vertices = {a, b, c, a + height * e, b + height * e, c + height * e};
  m.faces = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
  if (signed_volume(m) < 0)
    for (Triangle& t : m.faces) std::swap(t[1], t[2]);
  return m;
}

//! A unit cube with a thin tetrahedral spike on its top face, leaning along
//! (1, 1, 1): the three sides of its tip (vertex 11) have normals of mixed
//! signs, so no axis sees the tip, whatever the refinement.
Mesh make_cube_with_diagonal_spike() {
  const double c = (0.4 + 0.6 + 0.45) / 3, l = 0.5 / std::sqrt(3.0);
  Mesh m;
  m.vertices = {{0, 0, 0},      {1, 0, 0},        {1, 1, 0},        {0, 1, 0},        {0, 0, 1},         {1, 0, 1},
                {1, 1, 1},      {0, 1, 1},        {0.4, 0.4, 1},    {0.6, 0.45, 1},   {0.45, 0.6, 1},    {c + l, c + l, 1 + l}};
  m.faces = {{0, 2, 1}, {0, 3, 2}, {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},  {2, 3, 7},  {2, 7, 6},  {3, 0, 4},  {3, 4, 7},
             {4, 5, 9}, {4, 9, 8}, {5, 6, 9}, {6, 10, 9}, {6, 7, 10}, {7, 8, 10}, {7, 4, 8}, {8, 9, 11}, {9, 10, 11}, {10, 8, 11}};
  return m;
}

bool grow_succeeds(const Mesh& mesh) {
  try {
    grow_boxes(mesh, GrowOptions{});
    return true;
  } catch (const AlgorithmError&) {
    return false;
  }
}

TEST(RepairInfeasibleFeatures, ObliqueWedgeHasItsSharpEdgeAndGrowFails) {
  const Mesh wedge = make_oblique_wedge();
  const FeasibilityResult features = find_infeasible_features(wedge);
  ASSERT_FALSE(features.feasible());
  EXPECT_EQ(features.features.front().kind, InfeasibleFeature::Kind::Edge);
  EXPECT_EQ(features.features.front().vertex0, 0);
  EXPECT_EQ(features.features.front().vertex1, 3);
  // Exactly one crease: the sharp edge (the blunt edges share an axis).
  EXPECT_EQ(features.num_edges, 1u);
  EXPECT_FALSE(grow_succeeds(wedge));
}

TEST(RepairInfeasibleFeatures, FeasibleMeshComesBackBitForBit) {
  const Mesh box = test::make_box_mesh(Vec3(0, 0, 0), Vec3(1, 2, 3));
  const RepairResult r = repair_infeasible_features(box, RepairOptions{});
  EXPECT_EQ(r.mesh.vertices, box.vertices);
  EXPECT_EQ(r.mesh.faces, box.faces);
  EXPECT_EQ(r.report.num_features, 0);
  EXPECT_EQ(r.report.num_rounds, 0);
  EXPECT_EQ(r.report.num_faces_new, 0);
  EXPECT_EQ(r.report.max_deviation, 0.0);

  Mesh joint = read_mesh(test::data_path("joint.off"));
  ASSERT_TRUE(find_infeasible_features(joint).feasible());
  const RepairResult rj = repair_infeasible_features(joint, RepairOptions{});
  EXPECT_EQ(rj.mesh.vertices, joint.vertices);
  EXPECT_EQ(rj.mesh.faces, joint.faces);
}

void expect_repaired(const Mesh& input, const RepairResult& r, const RepairOptions& o) {
  EXPECT_GT(r.report.num_features, 0);
  EXPECT_GT(r.report.num_rounds, 0);
  EXPECT_GT(r.report.num_faces_new, 0);
  EXPECT_GT(r.report.num_faces_removed, 0);
  EXPECT_EQ(static_cast<int>(r.mesh.faces.size()) - r.report.num_faces_new,
            static_cast<int>(input.faces.size()) - r.report.num_faces_removed);  // the rest is unchanged
  EXPECT_TRUE(find_infeasible_features(r.mesh).feasible());
  Mesh check = r.mesh;
  EXPECT_NO_THROW(require_closed_solid(check));
  EXPECT_EQ(check.vertices, r.mesh.vertices);  // not flipped: still outward
  // Input vertices keep their ids.
  ASSERT_GE(r.mesh.vertices.size(), input.vertices.size());
  // Deviation: reported, positive, below the cap, and below its bound.
  EXPECT_GT(r.report.max_deviation, 0.0);
  EXPECT_GT(r.report.hausdorff_error, 0.0);
  EXPECT_LE(r.report.max_deviation_fraction(), o.max_deviation);
  EXPECT_GT(r.report.mean_deviation, 0.0);
  EXPECT_LE(r.report.mean_deviation, r.report.max_deviation * (1 + 1e-9));
  EXPECT_NEAR(r.report.bbox_diagonal, bounding_box(input).diagonal(), 1e-12);
}

//! The repair of `input` with one thread is `r`, bit for bit (deterministic).
void expect_same_with_one_thread(const Mesh& input, const RepairOptions& o, const RepairResult& r) {
  RepairResult one;
  {
    ThreadLimit limit(1);
    one = repair_infeasible_features(input, o);
  }
  EXPECT_EQ(one.mesh.vertices, r.mesh.vertices);
  EXPECT_EQ(one.mesh.faces, r.mesh.faces);
  EXPECT_EQ(one.report.max_deviation, r.report.max_deviation);
}

TEST(RepairInfeasibleFeatures, ObliqueWedgeIsRepaired) {
  const Mesh wedge = make_oblique_wedge();
  const RepairOptions o{};
  const RepairResult r = repair_infeasible_features(wedge, o);
  expect_repaired(wedge, r, o);
  EXPECT_GE(r.report.num_creases, 1);
  // Known gap: grow_boxes still fails on 6 faces of the repaired wedge after
  // its 8 refinement rounds (not asserted here; see the repair report).
  // The surface away from the sharp edge has not moved: the blunt corners
  // are still there.
  for (int v : {1, 2, 4, 5}) EXPECT_EQ(r.mesh.vertices[static_cast<std::size_t>(v)], wedge.vertices[static_cast<std::size_t>(v)]);
}

TEST(RepairInfeasibleFeatures, SameResultWithOneThread) {
  const Mesh wedge = make_oblique_wedge();
  const RepairResult all = repair_infeasible_features(wedge, RepairOptions{});
  RepairResult one;
  {
    ThreadLimit limit(1);
    one = repair_infeasible_features(wedge, RepairOptions{});
  }
  EXPECT_EQ(all.mesh.vertices, one.mesh.vertices);
  EXPECT_EQ(all.mesh.faces, one.mesh.faces);
  EXPECT_EQ(all.report.max_deviation, one.report.max_deviation);
}

TEST(RepairInfeasibleFeatures, DiagonalSpikeTipIsRepairedLocally) {
  const Mesh spike = make_cube_with_diagonal_spike();
  Mesh check = spike;
  ASSERT_NO_THROW(require_closed_solid(check));
  const FeasibilityResult features = find_infeasible_features(spike);
  ASSERT_EQ(features.num_vertices, 1u);
  EXPECT_EQ(features.num_edges, 0u);
  EXPECT_EQ(features.features.front().vertex0, 11);
  EXPECT_FALSE(features.features.front().splittable);
  const RepairOptions o{};
  const RepairResult r = repair_infeasible_features(spike, o);
  expect_repaired(spike, r, o);
  EXPECT_EQ(r.report.num_vertices, 1);
  // Only the spike changed: the cube's corners are where they were.
  for (int v = 0; v < 8; ++v) EXPECT_EQ(r.mesh.vertices[static_cast<std::size_t>(v)], spike.vertices[static_cast<std::size_t>(v)]);
  expect_same_with_one_thread(spike, o, r);
}

TEST(RepairInfeasibleFeatures, AnchorFlukeTipsAreStraightened) {
  // The two corner vertices of anchor.off (infeasible in every frame) sit
  // 0.0015 off the crease their neighbours span; straightening it is enough.
  const Mesh anchor = read_mesh(test::data_path("anchor.off"));
  const FeasibilityResult features = find_infeasible_features(anchor);
  ASSERT_EQ(features.num_vertices, 2u);
  const RepairOptions o{};
  const RepairResult r = repair_infeasible_features(anchor, o);
  expect_repaired(anchor, r, o);
  EXPECT_LE(r.report.max_deviation_fraction(), 0.002);
  EXPECT_LE(r.report.num_faces_new, 40);
  // Regression (machine STL of block 044 not a solid in float32): the move
  // of input vertex 501 (0.0460865, 0.0960186, 0.122067), on the plane
  // y = 0.0960186 of its neighbours, changed its y by 8.7e-13 (rounding of
  // the projection); the box plane through it then cut an 8.7e-13 sheet.
  // A moved input vertex keeps every coordinate it does not really change.
  const double diagonal = bounding_box(anchor).diagonal();
  std::size_t moved = 0;
  for (std::size_t v = 0; v < anchor.vertices.size(); ++v)
    for (int k = 0; k < 3; ++k) {
      const double change = std::abs(r.mesh.vertices[v][k] - anchor.vertices[v][k]);
      EXPECT_TRUE(change == 0.0 || change > 1e-9 * diagonal) << "vertex " << v << " coordinate " << k << ": " << change;
      if (change > 0) ++moved;
    }
  EXPECT_GT(moved, 0u);
  EXPECT_EQ(r.mesh.vertices[501].y(), anchor.vertices[501].y());
}

//! The star of a ridge peak (vertex 0) closed by a cone to vertex 9, after
//! vertex 15 of decimated_knight.off (offsets x100): top faces with normals
//! near (0.25 0.07 0.96), an overhanging side near (-0.96 -0.2 -0.2), both
//! ridge edges (0-3, 0-7) descending. Vertex 0 is its only infeasible
//! feature (not splittable): the top corner (0, 1, 2) faces +x, +y, +z and
//! lies in the open orthant (+, +, -), which the side faces (facing -x, -y,
//! -z) enter too.
Mesh make_ridge_peak() {
  Mesh m;
  m.vertices = {{0, 0, 0},           {3.35, 2.89, -1.14}, {2.26, 5.06, -1.00},  {0.02, 4.53, -2.03},
                {0.03, 3.95, -3.88}, {0.75, 1.52, -7.59}, {1.14, -1.30, -2.22}, {0.47, -3.33, -0.26},
                {2.91, -0.60, -0.66}, {2.59, 1.43, -3.87}};
  for (int i = 0; i < 8; ++i) {
    const int a = 1 + i, b = 1 + (i + 1) % 8;
    m.faces.push_back({0, a, b});
    m.faces.push_back({9, b, a});
  }
  return m;
}

TEST(RepairInfeasibleFeatures, RidgePeakIsChamfered) {
  const Mesh peak = make_ridge_peak();
  Mesh check = peak;
  ASSERT_NO_THROW(require_closed_solid(check));
  const FeasibilityResult features = find_infeasible_features(peak);
  ASSERT_EQ(features.size(), 1u);
  EXPECT_EQ(features.features.front().kind, InfeasibleFeature::Kind::Vertex);
  EXPECT_EQ(features.features.front().vertex0, 0);
  EXPECT_FALSE(features.features.front().splittable);
  const RepairOptions o{};
  const RepairResult r = repair_infeasible_features(peak, o);
  expect_repaired(peak, r, o);
  // Chamfered at the refined peak, a small strip: without the chamfer only
  // stage B's fillet repaired it (1214 faces, 0.0013 of the diagonal).
  EXPECT_LE(r.report.max_deviation_fraction(), 0.0005);
  EXPECT_LE(r.mesh.faces.size(), 600u);
  for (int v = 1; v < 10; ++v) EXPECT_EQ(r.mesh.vertices[static_cast<std::size_t>(v)], peak.vertices[static_cast<std::size_t>(v)]);
  expect_same_with_one_thread(peak, o, r);
}

TEST(RepairInfeasibleFeatures, DecimatedKnightRidgePeaksAreChamfered) {
  // decimated_knight.off (infeasible in every frame; decompose keeps the
  // input frame): the local edits and refinement leave 4 vertices on sharp
  // ridges (normals about 114 degrees apart, e.g. (0.27 0.07 0.96) and
  // (-0.96 -0.25 -0.14) at vertex 15) where the ridge peaks: both sides
  // reach into one open orthant, so no axis sees a corner there, and no
  // single-vertex move or smoothing fixes it. Before the ridge chamfer the
  // repair ended there (and stage B did not converge either).
  const Mesh knight = rotate_into_frame(read_mesh(test::data_path("decimated_knight.off")),
                                        Eigen::Matrix3d::Identity(), OrientOptions{}.snap_tolerance);
  const FeasibilityResult features = find_infeasible_features(knight);
  ASSERT_EQ(features.size(), 59u);
  const RepairOptions o{};
  const RepairResult r = repair_infeasible_features(knight, o);
  expect_repaired(knight, r, o);
  expect_same_with_one_thread(knight, o, r);
}

TEST(RepairInfeasibleFeatures, LocalExactTestCountsLikeTheWholeMesh) {
  // The repair decides each edit on the edited region only: the difference
  // of the local counts must be that of the whole mesh.
  const Mesh spike = make_cube_with_diagonal_spike();
  const FeasibilityResult whole = find_infeasible_features(spike);
  std::vector<int> all(spike.num_vertices());
  for (std::size_t v = 0; v < all.size(); ++v) all[v] = static_cast<int>(v);
  EXPECT_EQ(find_infeasible_features(spike, FeasibilityOptions{.only_vertices = all}).size(), whole.size());
  const FeasibilityResult tip = find_infeasible_features(spike, FeasibilityOptions{.only_vertices = {11}});
  ASSERT_EQ(tip.size(), 1u);
  EXPECT_EQ(tip.features.front().vertex0, 11);
  EXPECT_TRUE(find_infeasible_features(spike, FeasibilityOptions{.only_vertices = {0, 1, 2}}).feasible());
  const Mesh wedge = make_oblique_wedge();
  // The sharp edge (0, 3) is found from either end, once.
  const FeasibilityResult from3 =
      find_infeasible_features(wedge, FeasibilityOptions{.check_vertices = false, .only_vertices = {3}});
  ASSERT_EQ(from3.size(), 1u);
  EXPECT_EQ(from3.features.front().vertex0, 0);
  EXPECT_EQ(from3.features.front().vertex1, 3);
  EXPECT_EQ(find_infeasible_features(wedge, FeasibilityOptions{.check_vertices = false, .only_vertices = {0, 3}}).size(),
            1u);
  EXPECT_THROW(find_infeasible_features(wedge, FeasibilityOptions{.only_vertices = {6}}), InvalidArgumentError);
}

TEST(RepairInfeasibleFeatures, CapsAreEnforced) {
  const Mesh wedge = make_oblique_wedge();
  EXPECT_THROW(repair_infeasible_features(wedge, RepairOptions{.max_deviation = 1e-7}), AlgorithmError);
  EXPECT_THROW(repair_infeasible_features(wedge, RepairOptions{.max_rounds = 0}), AlgorithmError);
  EXPECT_THROW(repair_infeasible_features(wedge, RepairOptions{.max_deviation = 0}), InvalidArgumentError);
  EXPECT_THROW(repair_infeasible_features(wedge, RepairOptions{.lambda = 0.5, .mu = -0.4}), InvalidArgumentError);
}

TEST(RepairInfeasibleFeatures, PartHasInfeasibleCreasesWhereGrowFails) {
  const Mesh part = read_mesh(test::data_path("part.off"));
  const FeasibilityResult features = find_infeasible_features(part);
  ASSERT_FALSE(features.feasible());
  EXPECT_EQ(features.features.front().kind, InfeasibleFeature::Kind::Edge);
  EXPECT_FALSE(grow_succeeds(part));
}

TEST(RepairInfeasibleFeatures, DecomposeRepairsInTheChosenFrameOrRefusesWithExact) {
  const Mesh wedge = make_oblique_wedge();
  DecomposeOptions o;
  o.orient = false;  // the input frame, where the sharp edge is infeasible
  o.repair = false;  // --exact: the early refusal, naming the features
  try {
    decompose(wedge, o);
    ADD_FAILURE() << "--exact decomposed an infeasible wedge";
  } catch (const AlgorithmError& e) {
    EXPECT_NE(std::string(e.what()).find("no exact height-field decomposition exists in the input frame"),
              std::string::npos)
        << e.what();
    EXPECT_EQ(std::string(e.what()).find("local repair"), std::string::npos) << e.what();
  }
  // Default: the repair runs in that frame; a cap it cannot meet fails it
  // (known gap: with a reachable cap the repaired wedge still has faces grow
  // cannot cover after 8 refinement levels, so it is not decomposed here).
  o.repair = true;
  o.max_deviation = 1e-7;
  try {
    decompose(wedge, o);
    ADD_FAILURE() << "decomposed the wedge within a 1e-7 deviation";
  } catch (const AlgorithmError& e) {
    EXPECT_NE(std::string(e.what()).find("the local repair of infeasible features failed"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("--max-deviation"), std::string::npos) << e.what();
  }
  o.max_deviation = 0;
  EXPECT_THROW(decompose(wedge, o), InvalidArgumentError);
  // A feasible input is not repaired.
  o.max_deviation = 0.005;
  const DecomposeResult box = decompose(test::make_box_mesh(Vec3(0, 0, 0), Vec3(1, 2, 3)), o);
  EXPECT_FALSE(box.repaired_input.has_value());
  EXPECT_EQ(box.repair.num_features, 0);
  EXPECT_EQ(box.blocks.size(), 1u);
}

}  // namespace
}  // namespace subfab
