// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/fidelity/find_infeasible_features.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "support/box_shapes.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/orient_mesh.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab {
namespace {

//! The corner tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1): three faces on
//! the coordinate planes, one facing (1,1,1). One block along +z holds it all.
Mesh corner_tetrahedron() {
  Mesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

//! A thin wedge hanging below the edge (0,0,0)-(1,1,0): the edge lies in the
//! plane z = 0 and both faces along it go down, with outward normals
//! (-1, 1, -0.2) and (1, -1, 0.4): opposite signs in every coordinate, so no
//! milling axis sees both, and every box holding a piece of the edge holds
//! both faces next to it. (grow_boxes' impossible_crease() skips edges in an
//! axis-aligned plane; this one is impossible all the same.)
Mesh hanging_wedge() {
  Mesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(0.6, 0.4, -1), Vec3(0.7, 0.3, -1)};
  m.faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  return m;
}

Mesh turned(Mesh m, const Eigen::Matrix3d& r) {
  transform_mesh(m, r, Vec3::Zero());
  return m;
}

bool lists_edge(const FeasibilityResult& r, int a, int b) {
  return std::any_of(r.features.begin(), r.features.end(), [&](const InfeasibleFeature& f) {
    return f.kind == InfeasibleFeature::Kind::Edge && f.vertex0 == std::min(a, b) && f.vertex1 == std::max(a, b);
  });
}

bool lists_vertex(const FeasibilityResult& r, int v) {
  return std::any_of(r.features.begin(), r.features.end(), [&](const InfeasibleFeature& f) {
    return f.kind == InfeasibleFeature::Kind::Vertex && f.vertex0 == v;
  });
}

TEST(FindInfeasibleFeatures, AxisAlignedSolidsAreFeasible) {
  for (const Mesh& m : {test::make_box_mesh(Vec3(0, 0, 0), Vec3(1, 2, 3)), test::make_l_shape(), test::make_t_shape(),
                        corner_tetrahedron()}) {
    const FeasibilityResult r = find_infeasible_features(m);
    EXPECT_TRUE(r.feasible());
    EXPECT_EQ(r.num_edges + r.num_vertices, r.size());
  }
}

TEST(FindInfeasibleFeatures, CreaseInAnAxisPlaneWithBothFacesBelowIt) {
  const Mesh wedge = hanging_wedge();
  const FeasibilityResult r = find_infeasible_features(wedge);
  ASSERT_TRUE(lists_edge(r, 0, 1));
  const auto edge = std::find_if(r.features.begin(), r.features.end(),
                                 [](const InfeasibleFeature& f) { return f.kind == InfeasibleFeature::Kind::Edge; });
  EXPECT_EQ(edge->vertex0, 0);
  EXPECT_EQ(edge->vertex1, 1);
  EXPECT_TRUE((edge->face == 0 && edge->blocking_face == 1) || (edge->face == 1 && edge->blocking_face == 0));
  // Mirrored through z = 0 the faces go up instead: still impossible.
  Eigen::Matrix3d mirror = Eigen::Matrix3d::Identity();
  mirror(2, 2) = -1;
  Mesh up = turned(wedge, mirror);
  for (auto& f : up.faces) std::swap(f[1], f[2]);
  EXPECT_TRUE(lists_edge(find_infeasible_features(up), 0, 1));
  // An exact relabelling of the axes (90 degrees about x) changes nothing.
  Eigen::Matrix3d relabel;
  relabel << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  const FeasibilityResult q = find_infeasible_features(turned(wedge, relabel));
  EXPECT_EQ(q.num_edges, r.num_edges);
  EXPECT_EQ(q.num_vertices, r.num_vertices);
  EXPECT_TRUE(lists_edge(q, 0, 1));
}

// Within a tolerance a face may lean past vertical (tolerance_allowances()):
// the hanging wedge's crease (normals of opposite signs in every coordinate)
// is feasible once one of its two faces is allowed along any axis (both then
// face a common direction); allowances of the other faces do not help, and a
// wrong-sized list is refused.
TEST(FindInfeasibleFeatures, AllowedOverhangsMakeACreaseFeasible) {
  const Mesh wedge = hanging_wedge();
  std::vector<std::uint8_t> allowed(wedge.num_faces(), 0);
  FeasibilityOptions o;
  o.allowed_overhangs = &allowed;
  EXPECT_TRUE(lists_edge(find_infeasible_features(wedge, o), 0, 1));
  allowed[0] = 1u << 0;  // face 0 along x: it faces +x too, as face 1 does
  EXPECT_FALSE(lists_edge(find_infeasible_features(wedge, o), 0, 1));
  allowed[0] = 1u << 1;  // along y: face 0 faces -y too, as face 1 does
  EXPECT_FALSE(lists_edge(find_infeasible_features(wedge, o), 0, 1));
  allowed[0] = 1u << 2;  // along z: face 0 faces +z too, as face 1 does
  EXPECT_FALSE(lists_edge(find_infeasible_features(wedge, o), 0, 1));
  allowed[0] = 0;
  allowed[2] = allowed[3] = 7;  // the other faces: the crease stays
  EXPECT_TRUE(lists_edge(find_infeasible_features(wedge, o), 0, 1));
  allowed.pop_back();
  EXPECT_THROW(find_infeasible_features(wedge, o), InvalidArgumentError);
}

// A sharp crease is impossible in one frame and fine in another: the corner
// tetrahedron is one block in its frame, but turned generically its edges
// (normals 125 degrees apart at the slanted face) leave the axis planes.
TEST(FindInfeasibleFeatures, DependsOnTheFrame) {
  const Mesh tet = corner_tetrahedron();
  EXPECT_TRUE(find_infeasible_features(tet).feasible());
  const Mesh tilted = turned(tet, Eigen::AngleAxisd(0.6, Vec3(1, -2, 0.5).normalized()).toRotationMatrix());
  const FeasibilityResult r = find_infeasible_features(tilted);
  EXPECT_FALSE(r.feasible());
  EXPECT_GT(r.num_edges, 0u);
  // Orientation picks a frame free of them.
  const OrientResult o = orient_mesh(tilted);
  EXPECT_TRUE(o.infeasible.feasible());
  EXPECT_TRUE(find_infeasible_features(rotate_into_frame(tilted, o.rotation, OrientOptions{}.snap_tolerance)).feasible());
  // Without the check, the same candidates in the same order, first chosen.
  const OrientResult unchecked = orient_mesh(tilted, {.check_feasibility = false});
  EXPECT_EQ(unchecked.candidates.size(), o.candidates.size());
  EXPECT_EQ(unchecked.chosen, 0u);
}

// The real failures grow_boxes reported (sweep of the models at the default
// settings) are predicted, and models that decompose are not flagged.
TEST(FindInfeasibleFeatures, PredictsGrowOnRealModels) {
  // part.off: grow stops at the crease between faces 3 and 224.
  const Mesh part = read_mesh(test::data_path("part.off"));
  const FeasibilityResult p = find_infeasible_features(part);
  const Triangle& t3 = part.faces[3];
  const Triangle& t224 = part.faces[224];
  std::vector<int> shared;
  for (int v : t3)
    if (std::find(t224.begin(), t224.end(), v) != t224.end()) shared.push_back(v);
  ASSERT_EQ(shared.size(), 2u);
  EXPECT_TRUE(lists_edge(p, shared[0], shared[1]));
  // anchor.off: grow refines 8 times around two vertices and gives up.
  EXPECT_EQ(find_infeasible_features(read_mesh(test::data_path("anchor.off"))).num_vertices, 2u);
  // bunny_lowres.off decomposes in its frame; in the frame of the energy
  // optimum grow failed on the six faces around vertex 962 (a cone tip).
  const Mesh bunny = read_mesh(test::data_path("bunny_lowres.off"));
  EXPECT_TRUE(find_infeasible_features(bunny).feasible());
  const OrientResult best = orient_mesh(bunny, {.min_relative_gain = 0, .check_feasibility = false});
  const FeasibilityResult b = find_infeasible_features(turned(bunny, best.rotation));
  EXPECT_TRUE(lists_vertex(b, 962));
  // Models that decompose at the default settings.
  for (const char* name : {"cross.off", "joint.off", "spot.obj", "fandisk.obj", "moai.obj"})
    EXPECT_TRUE(find_infeasible_features(read_mesh(test::data_path(name))).feasible()) << name;
}

TEST(FindInfeasibleFeatures, ThreadIndependentAndDescribed) {
  const Mesh knight = read_mesh(test::data_path("decimated_knight.off"));
  const FeasibilityResult many = find_infeasible_features(knight);
  FeasibilityResult one;
  {
    ThreadLimit limit(1);
    one = find_infeasible_features(knight);
  }
  ASSERT_EQ(one.size(), many.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one.features[i].vertex0, many.features[i].vertex0);
    EXPECT_EQ(one.features[i].vertex1, many.features[i].vertex1);
    EXPECT_EQ(one.features[i].face, many.features[i].face);
  }
  ASSERT_GT(many.size(), 3u);
  const std::string text = describe_infeasible_features(many, knight, 2);
  EXPECT_NE(text.find(many.features[0].kind == InfeasibleFeature::Kind::Edge ? "edge (" : "vertex ("), std::string::npos);
  EXPECT_NE(text.find(", ..."), std::string::npos);
  EXPECT_EQ(describe_infeasible_features(FeasibilityResult{}, knight), "");
}

TEST(FindInfeasibleFeatures, RefusesAnOpenMesh) {
  Mesh open = corner_tetrahedron();
  open.faces.pop_back();
  EXPECT_THROW(find_infeasible_features(open), InvalidMeshError);
}

}  // namespace
}  // namespace subfab
