// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/analyze_mesh.h"

#include <gtest/gtest.h>

#include <limits>

#include "support/test_shapes.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

std::vector<std::string> failed_checks(const MeshReport& report) {
  std::vector<std::string> names;
  for (const auto& check : report.checks)
    if (check.failed()) names.push_back(check.name);
  return names;
}

TEST(AnalyzeMesh, CubeMeasures) {
  const MeshReport r = analyze_mesh(test::cube(Vec3(1, 2, 3), 2.0));
  EXPECT_EQ(r.num_vertices, 8u);
  EXPECT_EQ(r.num_faces, 12u);
  EXPECT_EQ(r.num_edges, 18u);
  EXPECT_EQ(r.checks.size(), 11u);
  EXPECT_TRUE(r.all_passed()) << testing::PrintToString(failed_checks(r));
  EXPECT_EQ(r.closed, true);
  EXPECT_EQ(r.manifold, true);
  EXPECT_EQ(r.oriented, true);
  EXPECT_EQ(r.outward, true);
  EXPECT_EQ(r.self_intersecting, false);
  EXPECT_EQ(r.num_components, 1u);
  EXPECT_EQ(r.genus, 0);
  ASSERT_TRUE(r.bbox);
  EXPECT_EQ(r.bbox->min, Vec3(1, 2, 3));
  EXPECT_EQ(r.bbox->max, Vec3(3, 4, 5));
  EXPECT_DOUBLE_EQ(*r.diagonal, std::sqrt(12.0));
  EXPECT_DOUBLE_EQ(*r.area, 24.0);
  EXPECT_DOUBLE_EQ(*r.volume, 8.0);
  // 12 sides of length 2, 6 diagonals of length 2 sqrt(2).
  EXPECT_DOUBLE_EQ(*r.average_edge_length, (12 * 2.0 + 6 * 2 * std::sqrt(2.0)) / 18);
}

TEST(AnalyzeMesh, GenusOfTorusAndTwoTori) {
  EXPECT_EQ(analyze_mesh(test::torus()).genus, 1);
  const Mesh two = test::append(test::torus(), test::torus(12, 8, 2.0, 0.5, Vec3(10, 0, 0)));
  const MeshReport r = analyze_mesh(two);
  EXPECT_EQ(r.num_components, 2u);
  EXPECT_EQ(r.genus, 2);
  EXPECT_TRUE(r.all_passed());
}

TEST(AnalyzeMesh, OpenMeshHasNoGenusNorVolume) {
  Mesh m = test::cube();
  m.faces.erase(m.faces.begin(), m.faces.begin() + 2);
  const MeshReport r = analyze_mesh(m);
  EXPECT_EQ(r.closed, false);
  EXPECT_EQ(r.num_boundary_edges, 4u);
  EXPECT_EQ(r.num_holes, 1u);
  EXPECT_FALSE(r.genus);
  EXPECT_FALSE(r.volume);
  EXPECT_EQ(r.find("outward_orientation")->status, CheckStatus::Skipped);
  EXPECT_EQ(failed_checks(r), (std::vector<std::string>{"boundary_edges"}));
}

TEST(AnalyzeMesh, InwardCubeIsReported) {
  const MeshReport r = analyze_mesh(test::flipped(test::cube()));
  EXPECT_EQ(r.outward, false);
  EXPECT_EQ(r.oriented, true);
  EXPECT_EQ(r.genus, 0);
  EXPECT_DOUBLE_EQ(*r.volume, -1.0);
}

TEST(AnalyzeMesh, BadIndicesSkipEverythingElse) {
  Mesh m = test::cube();
  m.faces[4][2] = 42;
  const MeshReport r = analyze_mesh(m);
  EXPECT_EQ(failed_checks(r), (std::vector<std::string>{"face_indices"}));
  for (std::size_t i = 2; i < r.checks.size(); ++i)
    EXPECT_EQ(r.checks[i].status, CheckStatus::Skipped) << r.checks[i].name;
  EXPECT_FALSE(r.closed);
  EXPECT_FALSE(r.bbox);
}

TEST(AnalyzeMesh, EmptyMeshIsNotCalledClosed) {
  const MeshReport r = analyze_mesh(Mesh{});
  EXPECT_FALSE(r.closed);
  EXPECT_FALSE(r.genus);
  EXPECT_EQ(r.find("boundary_edges")->status, CheckStatus::Skipped);
  EXPECT_NE(r.find("boundary_edges")->message.find("no faces"), std::string::npos);
}

TEST(AnalyzeMesh, NanCoordinatesSkipGeometry) {
  Mesh m = test::cube();
  m.vertices[2].z() = std::numeric_limits<double>::quiet_NaN();
  const MeshReport r = analyze_mesh(m);
  EXPECT_EQ(failed_checks(r), (std::vector<std::string>{"finite_coordinates"}));
  EXPECT_EQ(r.closed, true);  // topology is still known
  EXPECT_FALSE(r.self_intersecting);
  EXPECT_FALSE(r.area);
}

TEST(AnalyzeMesh, SelfIntersectionCanBeSwitchedOff) {
  const MeshReport r = analyze_mesh(test::cube(), {.self_intersections = false});
  EXPECT_EQ(r.find("self_intersections")->status, CheckStatus::Skipped);
  EXPECT_FALSE(r.self_intersecting);
}

// Real data: every closed model bundled in data/ passes every check.
TEST(AnalyzeMesh, EveryClosedBundledModelPasses) {
  for (const char* name : {"bunny_lowres.off", "spot.obj", "fandisk.obj", "decimated_knight.off",
                           "cross.off", "part.off", "joint.off", "anchor.off", "rotor.off",
                           "moai.obj"}) {
    const MeshReport r = analyze_mesh(read_mesh(test::data_path(name)));
    EXPECT_TRUE(r.all_passed()) << name << ": " << testing::PrintToString(failed_checks(r));
    EXPECT_EQ(r.num_components, 1u) << name;
    EXPECT_TRUE(r.genus.has_value()) << name;
    EXPECT_GT(*r.volume, 0) << name;
  }
}

TEST(AnalyzeMesh, GenusOfBundledModelsMatchesManifest) {
  EXPECT_EQ(analyze_mesh(read_mesh(test::data_path("anchor.off"))).genus, 4);
  EXPECT_EQ(analyze_mesh(read_mesh(test::data_path("joint.off"))).genus, 2);
  EXPECT_EQ(analyze_mesh(read_mesh(test::data_path("rotor.off"))).genus, 1);
  EXPECT_EQ(analyze_mesh(read_mesh(test::data_path("fandisk.obj"))).genus, 0);
}

// The cow has one pinched vertex (MANIFEST.md) and, as CGAL's own
// Polygon_mesh_processing::self_intersections confirms, 81 intersecting face
// pairs (82 faces) elsewhere.
TEST(AnalyzeMesh, CowPinchedVertex253) {
  const MeshReport r = analyze_mesh(read_mesh(test::data_path("cow.obj")));
  const CheckResult* pinched = r.find("non_manifold_vertices");
  ASSERT_NE(pinched, nullptr);
  EXPECT_TRUE(pinched->failed());
  EXPECT_EQ(pinched->num_offending, 1u);
  EXPECT_EQ(pinched->examples, (std::vector<int>{253}));
  EXPECT_EQ(failed_checks(r),
            (std::vector<std::string>{"non_manifold_vertices", "self_intersections"}));
  EXPECT_EQ(r.find("self_intersections")->num_offending, 81u);
  EXPECT_EQ(r.closed, true);
  EXPECT_EQ(r.manifold, false);
  EXPECT_FALSE(r.genus);
}

TEST(AnalyzeMesh, TeapotIsOpen) {
  const MeshReport r = analyze_mesh(read_mesh(test::data_path("teapot.obj")));
  EXPECT_EQ(r.closed, false);
  EXPECT_EQ(r.num_boundary_edges, 1036u);  // MANIFEST.md
  EXPECT_EQ(r.num_components, 4u);
}

TEST(AnalyzeMesh, GenusOfSharedModels) {
  if (!test::have_shared_models()) GTEST_SKIP() << "../shared/models not present";
  for (const auto& [name, genus] : std::vector<std::pair<std::string, int>>{
           {"kitten.obj", 1}, {"bob.obj", 1}, {"fertility.off", 4}}) {
    const MeshReport r = analyze_mesh(read_mesh(test::models_path(name)),
                                      {.self_intersections = false});
    EXPECT_EQ(r.genus, genus) << name;
  }
}

}  // namespace
}  // namespace subfab
