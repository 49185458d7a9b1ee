// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/solid_index.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "support/block_test_shapes.h"
#include "support/box_shapes.h"
#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"

namespace subfab::detail {
namespace {

Mesh read_data(const std::string& name) { return read_mesh(test::data_path(name)); }

Box3 mesh_box(const Mesh& m) {
  const BoundingBox b = bounding_box(m);
  return Box3{b.min, b.max};
}

TEST(SolidIndex, CubeBoxIsValidForAllAxesAndCoversEverything) {
  const Mesh cube = test::make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const SolidIndex index(cube);
  const Box3 box = mesh_box(cube);
  for (Axis a : kAllAxes) {
    EXPECT_TRUE(index.box_is_valid(box, a)) << axis_name(a);
    EXPECT_EQ(index.faces_facing_away(a).size(), 2u) << axis_name(a);
    EXPECT_EQ(index.faces_covered(box, a).size(), 12u) << axis_name(a);
    // A larger box has the base face (facing away) in its interior.
    const Box3 bigger{Vec3(-1, -1, -1), Vec3(2, 2, 2)};
    EXPECT_FALSE(index.box_is_valid(bigger, a)) << axis_name(a);
  }
  // A box straddling the bottom face is invalid for +z but valid for -z.
  const Box3 straddle{Vec3(0.2, 0.2, -0.5), Vec3(0.8, 0.8, 0.5)};
  EXPECT_FALSE(index.box_is_valid(straddle, Axis::PosZ));
  EXPECT_TRUE(index.box_is_valid(straddle, Axis::NegZ));
  EXPECT_EQ(index.blocking_faces(straddle, Axis::PosZ).size(), 2u);
  // Half of the cube: the top face is covered for +z, the side faces
  // crossing the plane z = 0.5 are not inside it.
  const Box3 upper{Vec3(0, 0, 0.5), Vec3(1, 1, 1)};
  const auto covered = index.faces_covered(upper, Axis::PosZ);
  ASSERT_EQ(covered.size(), 2u);
  for (int f : covered) EXPECT_EQ(index.facing_sign(f, Axis::PosZ), 1);
  // A box beside the cube sharing its x = 1 plane: the cube's x = 1 face
  // lies in the box's min-x plane with the solid outside: not covered.
  const Box3 beside{Vec3(1, 0, 0), Vec3(2, 1, 1)};
  EXPECT_TRUE(index.faces_covered(beside, Axis::PosZ).empty());
  // A zero-thickness box covers nothing.
  EXPECT_TRUE(index.faces_covered(Box3{Vec3(0, 0, 1), Vec3(1, 1, 1)}, Axis::PosZ).empty());
}

TEST(SolidIndex, LShapeWholeBoxInvalidArmsValid) {
  const Mesh l = test::make_l_shape();
  const SolidIndex index(l);
  const Box3 whole = mesh_box(l);
  // Milled from +x, the upper arm's wall x = 1 (normal +x) is fine but the
  // inner wall y = 1 (normal +y) is parallel; the whole bbox is valid for
  // +-z (a prism) and invalid for the in-plane directions that see the notch.
  EXPECT_TRUE(index.box_is_valid(whole, Axis::PosZ));
  EXPECT_TRUE(index.box_is_valid(whole, Axis::NegZ));
  EXPECT_FALSE(index.box_is_valid(whole, Axis::NegX));  // wall x=1 faces +x: away from -x, inside the bbox
  EXPECT_FALSE(index.box_is_valid(whole, Axis::NegY));  // wall y=1 faces +y
  EXPECT_TRUE(index.box_is_valid(whole, Axis::PosX));
  EXPECT_TRUE(index.box_is_valid(whole, Axis::PosY));
  // The arms are valid boxes for every axis.
  const Box3 arm_x{Vec3(0, 0, 0), Vec3(2, 1, 1)};
  const Box3 arm_y{Vec3(0, 0, 0), Vec3(1, 2, 1)};
  for (Axis a : kAllAxes) {
    EXPECT_TRUE(index.box_is_valid(arm_x, a)) << axis_name(a);
    EXPECT_TRUE(index.box_is_valid(arm_y, a)) << axis_name(a);
  }
  // +z: the whole bbox covers everything (it is the L's own prism).
  EXPECT_EQ(index.faces_covered(whole, Axis::PosZ).size(), l.faces.size());
}

TEST(SolidIndex, LShapeRotatedSoThatZSeesTheNotch) {
  // Swap y and z: the L lies in the xz plane, its notch opens towards +x+z.
  Mesh l = test::make_l_shape();
  for (Vec3& v : l.vertices) std::swap(v.y(), v.z());
  for (Triangle& t : l.faces) std::swap(t[1], t[2]);  // the swap mirrors: restore orientation
  const SolidIndex index(l);
  EXPECT_GT(signed_volume(l), 0);
  const Box3 whole = mesh_box(l);
  // Milled from -z the notch's ceiling (z = 1 wall of the x-arm, normal +z)
  // faces away: a -z box spanning the whole bbox is invalid; from +z it is valid.
  EXPECT_TRUE(index.box_is_valid(whole, Axis::PosZ));
  EXPECT_FALSE(index.box_is_valid(whole, Axis::NegZ));
  const Box3 arm_x{Vec3(0, 0, 0), Vec3(2, 1, 1)};
  const Box3 arm_z{Vec3(0, 0, 0), Vec3(1, 1, 2)};
  EXPECT_TRUE(index.box_is_valid(arm_x, Axis::NegZ));
  EXPECT_TRUE(index.box_is_valid(arm_z, Axis::NegZ));
  EXPECT_EQ(index.blocking_faces(whole, Axis::NegZ).size(), 2u);  // the two triangles of the notch's wall
}

TEST(SolidIndex, TShape) {
  Mesh t = test::make_t_shape();
  for (Vec3& v : t.vertices) std::swap(v.y(), v.z());
  for (Triangle& f : t.faces) std::swap(f[1], f[2]);
  const SolidIndex index(t);
  const Box3 whole = mesh_box(t);
  // The bar is on top (z in [2,3]), the stem below. From +z the bar's
  // underside overhangs (faces -z): the whole bbox is invalid; from -z
  // everything is visible and the bar's top is the base.
  EXPECT_FALSE(index.box_is_valid(whole, Axis::PosZ));
  EXPECT_TRUE(index.box_is_valid(whole, Axis::NegZ));
  EXPECT_EQ(index.blocking_faces(whole, Axis::PosZ).size(), 4u);  // two underside rectangles
  EXPECT_TRUE(index.box_is_valid(Box3{Vec3(0, 0, 2), Vec3(3, 1, 3)}, Axis::PosZ));  // the bar alone
  EXPECT_TRUE(index.box_is_valid(Box3{Vec3(1, 0, 0), Vec3(2, 1, 3)}, Axis::PosZ));  // stem and bar middle
  EXPECT_FALSE(index.box_is_valid(Box3{Vec3(0.5, 0, 0), Vec3(2, 1, 3)}, Axis::PosZ));
  EXPECT_EQ(index.faces_covered(whole, Axis::NegZ).size(), t.faces.size());
}

TEST(SolidIndex, PushFaceFindsExactFirstContact) {
  Mesh t = test::make_t_shape();
  for (Vec3& v : t.vertices) std::swap(v.y(), v.z());
  for (Triangle& f : t.faces) std::swap(f[1], f[2]);
  const SolidIndex index(t);
  // A +z box over the stem and the middle of the bar, pushed along -x,
  // stops at x = 1 where the left arm's underside would enter it.
  const Box3 stem{Vec3(1, 0, 0), Vec3(2, 1, 3)};
  EXPECT_EQ(index.push_face(stem, Axis::PosZ, 0, -1, -5.0), 1.0);
  EXPECT_EQ(index.push_face(stem, Axis::PosZ, 0, +1, 5.0), 2.0);
  // Up: nothing faces -z above the bar: reaches the limit.
  EXPECT_EQ(index.push_face(stem, Axis::PosZ, 2, +1, 7.5), 7.5);
  // Down: the stem's bottom (z = 0, facing -z) may only be touched.
  EXPECT_EQ(index.push_face(stem, Axis::PosZ, 2, -1, -4.0), 0.0);
  // For -z nothing faces +z below the stem's top... but the bar's top
  // z = 3 faces +z: pushing a -z box up from below stops there.
  EXPECT_EQ(index.push_face(Box3{Vec3(0.5, 0, 2.2), Vec3(2.5, 1, 2.8)}, Axis::NegZ, 2, +1, 9.0), 3.0);
  // A +z box on the bar top pushed down stops at the underside z = 2.
  const Box3 bar_top{Vec3(0, 0, 2.5), Vec3(3, 1, 3)};
  EXPECT_EQ(index.push_face(bar_top, Axis::PosZ, 2, -1, -1.0), 2.0);
  // A sloped contact: not a grid value, but the result is exactly maximal.
  const Box3 thin{Vec3(0.25, 0.25, 2.9), Vec3(0.75, 0.75, 2.95)};
  const double t_down = index.push_face(thin, Axis::PosZ, 2, -1, -1.0);
  EXPECT_EQ(t_down, 2.0);
}

TEST(SolidIndex, PushFaceMatchesBruteForceOnRealData) {
  const Mesh mesh = read_data("bunny_lowres.off");
  const SolidIndex index(mesh);
  const BoundingBox bb = bounding_box(mesh);
  std::mt19937 rng(99);
  int moved = 0;
  for (int iter = 0; iter < 200; ++iter) {
    const int f = static_cast<int>(rng() % mesh.faces.size());
    const Axis axis = closest_axis(face_unit_normal(mesh, static_cast<std::size_t>(f)));
    const Box3 seed = index.face_box(f);
    if (!index.box_is_valid(seed, axis)) continue;
    const int dim = static_cast<int>(rng() % 3);
    const int side = (rng() % 2) ? 1 : -1;
    const double limit = side > 0 ? bb.max[dim] + 1 : bb.min[dim] - 1;
    const double t = index.push_face(seed, axis, dim, side, limit);
    Box3 at = seed;
    (side > 0 ? at.max[dim] : at.min[dim]) = t;
    EXPECT_TRUE(index.box_is_valid(at, axis));
    if (t != limit) {
      Box3 beyond = seed;
      (side > 0 ? beyond.max[dim] : beyond.min[dim]) = std::nextafter(t, limit);
      EXPECT_FALSE(index.box_is_valid(beyond, axis)) << "not maximal at iteration " << iter;
    }
    if (t != (side > 0 ? seed.max[dim] : seed.min[dim])) ++moved;
  }
  EXPECT_GT(moved, 50);
}

TEST(SolidIndex, AnyFaceAndNearFaceQueriesMatchLinearScans) {
  const Mesh mesh = read_data("fandisk.obj");
  const SolidIndex index(mesh);
  const BoundingBox bb = bounding_box(mesh);
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int hits = 0;
  for (int iter = 0; iter < 100; ++iter) {
    const Vec3 p = bb.min + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(bb.max - bb.min);
    const Vec3 q = p + 0.15 * Vec3(u(rng), u(rng), u(rng)).cwiseProduct(bb.max - bb.min);
    const Box3 box{p, q};
    bool any = false;
    std::vector<int> near;
    for (int f = 0; f < index.num_faces(); ++f) {
      any = any || index.face_meets_open_box(f, box);
      const Box3& fb = index.face_box(f);
      if ((fb.max.array() >= box.min.array()).all() && (fb.min.array() <= box.max.array()).all()) near.push_back(f);
    }
    EXPECT_EQ(index.any_face_meets_open_box(box), any);
    EXPECT_EQ(index.faces_near_closed_box(box), near);
    EXPECT_EQ(index.faces_meeting_open_box(box).empty(), !any);
    hits += any;
  }
  EXPECT_GT(hits, 10);
  EXPECT_LT(hits, 95);
}

TEST(SolidIndex, IsInsideOnCubeIncludingBoundaryPoints) {
  const Mesh cube = test::make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const SolidIndex index(cube);
  EXPECT_TRUE(index.is_inside(Vec3(0.5, 0.5, 0.5)));
  EXPECT_TRUE(index.is_inside(Vec3(0.5, 0.5, 0.5)));
  EXPECT_FALSE(index.is_inside(Vec3(1.5, 0.5, 0.5)));
  EXPECT_FALSE(index.is_inside(Vec3(0.5, 0.5, -0.5)));
  EXPECT_FALSE(index.is_inside(Vec3(0.5, 0.5, 1.5)));
  // Points on the diagonals of the faces (where the ray hits triangle edges).
  EXPECT_TRUE(index.is_inside(Vec3(0.25, 0.25, 0.5)));
  EXPECT_TRUE(index.is_inside(Vec3(0.75, 0.75, 0.1)));
  // Boundary points: p + (e, e^2, e^3). On the min faces the perturbation
  // goes inside; on the max faces outside.
  EXPECT_TRUE(index.is_inside(Vec3(0, 0.5, 0.5)));
  EXPECT_FALSE(index.is_inside(Vec3(1, 0.5, 0.5)));
  EXPECT_TRUE(index.is_inside(Vec3(0.5, 0.5, 0)));
  EXPECT_FALSE(index.is_inside(Vec3(0.5, 0.5, 1)));
  EXPECT_TRUE(index.is_inside(Vec3(0, 0, 0)));
  EXPECT_FALSE(index.is_inside(Vec3(1, 1, 1)));
  EXPECT_FALSE(index.is_inside(Vec3(0, 1, 0.5)));  // y = 1 face: perturbation leaves
}

TEST(SolidIndex, IsInsideAgreesWithWindingNumberOnRealData) {
  const Mesh mesh = read_data("spot.obj");
  const SolidIndex index(mesh);
  const BoundingBox bb = bounding_box(mesh);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int inside = 0;
  for (int iter = 0; iter < 300; ++iter) {
    const Vec3 p = bb.min + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(bb.max - bb.min);
    double omega = 0;  // generalised winding number (solid angles)
    for (const Triangle& t : mesh.faces) {
      const Vec3 a = mesh.vertices[static_cast<std::size_t>(t[0])] - p;
      const Vec3 b = mesh.vertices[static_cast<std::size_t>(t[1])] - p;
      const Vec3 c = mesh.vertices[static_cast<std::size_t>(t[2])] - p;
      const double la = a.norm(), lb = b.norm(), lc = c.norm();
      omega += 2 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
    }
    const double winding = omega / (4 * M_PI);
    if (std::abs(winding - std::round(winding)) > 0.1) continue;  // too close to the surface to trust
    EXPECT_EQ(index.is_inside(p), std::lround(winding) == 1) << p.transpose();
    inside += std::lround(winding) == 1;
  }
  EXPECT_GT(inside, 10);
}

TEST(SolidIndex, FacesFacingAwayUseExactSigns) {
  // A triangle whose normal's z component is exactly zero although its
  // vertices are not representable multiples (vertical wall at 45 deg).
  Mesh m;
  m.vertices = {Vec3(0.1, 0.3, 0.0), Vec3(0.3, 0.1, 0.0), Vec3(0.1, 0.3, 1.0)};
  m.faces = {{0, 1, 2}};
  const SolidIndex index(m);
  EXPECT_EQ(index.facing_sign(0, Axis::PosZ), 0);
  EXPECT_EQ(index.facing_sign(0, Axis::NegZ), 0);
  EXPECT_TRUE(index.faces_facing_away(Axis::PosZ).empty());
  EXPECT_EQ(index.facing_sign(0, Axis::PosX), -index.facing_sign(0, Axis::NegX));
}

TEST(SolidIndex, OverhangAllowanceRelaxesOnlyTheFacingTest) {
  // The barrel's lower side faces lean 5 degrees past vertical: they face
  // away from +z exactly, and face it under a 10-degree allowance, which
  // makes the whole bounding box valid for +z; the inside test is unchanged.
  const Mesh barrel = test::barrel_solid(1.0, 1.0, 5.0);
  const SolidIndex exact(barrel);
  const SolidIndex leaning(barrel, overhang_sine(10.0));
  const SolidIndex too_little(barrel, overhang_sine(4.0));
  const BoundingBox bb = bounding_box(barrel);
  const Box3 whole{bb.min, bb.max};
  EXPECT_EQ(exact.faces_facing_away(Axis::PosZ).size(), 10u);  // 2 bottom + 8 lower side triangles
  EXPECT_EQ(too_little.faces_facing_away(Axis::PosZ).size(), 10u);
  EXPECT_EQ(leaning.faces_facing_away(Axis::PosZ).size(), 2u);  // the bottom only
  EXPECT_FALSE(exact.box_is_valid(whole, Axis::PosZ));
  EXPECT_FALSE(too_little.box_is_valid(whole, Axis::PosZ));
  EXPECT_TRUE(leaning.box_is_valid(whole, Axis::PosZ));
  EXPECT_EQ(leaning.faces_covered(whole, Axis::PosZ).size(), barrel.faces.size());
  EXPECT_LT(exact.faces_covered(whole, Axis::PosZ).size(), barrel.faces.size());
  for (const Vec3& p : {Vec3(0, 0, 1), Vec3(1.05, 0, 1), Vec3(1.05, 0, 0.1)})
    EXPECT_EQ(exact.is_inside(p), leaning.is_inside(p)) << p.transpose();
}

TEST(SolidIndex, BaseFloorsMakeAnAllowanceDependOnTheBoxsBase) {
  // The T shape's bar (z in [2, 3]) overhangs the stem: its underside
  // (z = 2, facing -z) blocks every +z box reaching below it. Allowed for z
  // above the base floor 1.5, a +z box may hold it when its base lies at or
  // above z = 1.5, not lower.
  Mesh t = test::make_t_shape();
  for (Vec3& v : t.vertices) std::swap(v.y(), v.z());
  for (Triangle& f : t.faces) std::swap(f[1], f[2]);
  std::vector<std::uint8_t> allowed(t.faces.size(), 0);
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<std::array<double, 3>> floors(t.faces.size(), {-inf, -inf, -inf});
  int underside = 0;
  for (std::size_t f = 0; f < t.faces.size(); ++f) {
    const Vec3 n = face_unit_normal(t, f);
    if (n.z() < -0.5 && t.vertices[static_cast<std::size_t>(t.faces[f][0])].z() == 2.0) {
      allowed[f] = 4;
      floors[f][2] = 1.5;
      ++underside;
    }
  }
  ASSERT_EQ(underside, 4);
  const SolidIndex everywhere(t, 0.0, &allowed);  // no floors: the bits hold in every box
  const SolidIndex index(t, 0.0, &allowed, &floors);
  const Box3 whole = mesh_box(t);
  EXPECT_TRUE(everywhere.box_is_valid(whole, Axis::PosZ));
  EXPECT_FALSE(index.box_is_valid(whole, Axis::PosZ));  // base 0 < 1.5
  EXPECT_EQ(index.blocking_faces(whole, Axis::PosZ).size(), 4u);
  EXPECT_TRUE(index.has_conditional_faces(Axis::PosZ));
  EXPECT_FALSE(index.has_conditional_faces(Axis::NegZ));
  EXPECT_FALSE(index.conditional_faces_allow(whole, Axis::PosZ));
  const Box3 high{Vec3(0, 0, 1.5), Vec3(3, 1, 3)};
  const Box3 low{Vec3(0, 0, std::nextafter(1.5, 0.0)), Vec3(3, 1, 3)};
  EXPECT_TRUE(index.box_is_valid(high, Axis::PosZ));
  EXPECT_FALSE(index.box_is_valid(low, Axis::PosZ));
  EXPECT_TRUE(index.conditional_faces_allow(high, Axis::PosZ));
  // Coverage follows the base: the underside is covered by the high box only.
  int covered_high = 0, covered_low = 0;
  for (std::size_t f = 0; f < t.faces.size(); ++f)
    if (allowed[f]) {
      EXPECT_EQ(index.facing_sign(static_cast<int>(f), Axis::PosZ), -1);
      EXPECT_EQ(everywhere.facing_sign(static_cast<int>(f), Axis::PosZ), 0);
      EXPECT_EQ(index.base_floor(static_cast<int>(f), Axis::PosZ), 1.5);
      covered_high += index.face_covered(static_cast<int>(f), high, Axis::PosZ) ? 1 : 0;
      covered_low += index.face_covered(static_cast<int>(f), low, Axis::PosZ) ? 1 : 0;
    }
  EXPECT_EQ(covered_high, 4);
  EXPECT_EQ(covered_low, 0);
  // Pushing the bar's box down stops exactly at the floor; sideways at a
  // base above the floor nothing stops it; -z is unaffected.
  const Box3 bar_top{Vec3(0, 0, 2.5), Vec3(3, 1, 3)};
  EXPECT_EQ(index.push_face(bar_top, Axis::PosZ, 2, -1, -1.0), 1.5);
  EXPECT_EQ(everywhere.push_face(bar_top, Axis::PosZ, 2, -1, -1.0), 0.0);  // the stem's bottom
  const Box3 stem_high{Vec3(1, 0, 1.6), Vec3(2, 1, 3)};
  EXPECT_EQ(index.push_face(stem_high, Axis::PosZ, 0, -1, -5.0), -5.0);
  const Box3 stem{Vec3(1, 0, 0), Vec3(2, 1, 3)};
  EXPECT_EQ(index.push_face(stem, Axis::PosZ, 0, -1, -5.0), 1.0);
  EXPECT_TRUE(index.box_is_valid(whole, Axis::NegZ));
}

TEST(SolidIndex, PushFaceWithBaseFloorsMatchesBruteForceOnRealData) {
  // Random floors on the faces facing away from each axis: push_face's
  // result is valid and maximal (one double further is invalid).
  const Mesh mesh = read_data("bunny_lowres.off");
  const BoundingBox bb = bounding_box(mesh);
  std::mt19937 rng(7);
  std::vector<std::uint8_t> allowed(mesh.faces.size(), 0);
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<std::array<double, 3>> floors(mesh.faces.size(), {-inf, -inf, -inf});
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Vec3 n = face_unit_normal(mesh, f);
    for (int k = 0; k < 3; ++k) {
      if (rng() % 2) continue;
      allowed[f] = static_cast<std::uint8_t>(allowed[f] | (1u << k));
      // Base coordinate for the direction the face faces away from.
      const double lo = n[k] < 0 ? bb.min[k] : -bb.max[k], hi = n[k] < 0 ? bb.max[k] : -bb.min[k];
      floors[f][static_cast<std::size_t>(k)] = lo + (hi - lo) * static_cast<double>(rng() % 1000) / 1000.0;
    }
  }
  const SolidIndex index(mesh, 0.0, &allowed, &floors);
  int moved = 0, base_moves = 0;
  for (int iter = 0; iter < 300; ++iter) {
    const int f = static_cast<int>(rng() % mesh.faces.size());
    const Axis axis = closest_axis(face_unit_normal(mesh, static_cast<std::size_t>(f)));
    const Box3 seed = index.face_box(f);
    if (!index.box_is_valid(seed, axis)) continue;
    const int dim = iter % 2 ? axis_dimension(axis) : static_cast<int>(rng() % 3);
    const int side = (rng() % 2) ? 1 : -1;
    const double limit = side > 0 ? bb.max[dim] + 1 : bb.min[dim] - 1;
    const double t = index.push_face(seed, axis, dim, side, limit);
    Box3 at = seed;
    (side > 0 ? at.max[dim] : at.min[dim]) = t;
    EXPECT_TRUE(index.box_is_valid(at, axis)) << "iteration " << iter;
    if (t != limit) {
      Box3 beyond = seed;
      (side > 0 ? beyond.max[dim] : beyond.min[dim]) = std::nextafter(t, limit);
      EXPECT_FALSE(index.box_is_valid(beyond, axis)) << "not maximal at iteration " << iter;
    }
    if (t != (side > 0 ? seed.max[dim] : seed.min[dim])) {
      ++moved;
      base_moves += dim == axis_dimension(axis) && side == -axis_sign(axis) ? 1 : 0;
    }
  }
  EXPECT_GT(moved, 50);
  EXPECT_GT(base_moves, 10);
}

}  // namespace
}  // namespace subfab::detail
