// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/export_unfolding.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "subfab/mesh/read_mesh.h"
#include "support/test_support.h"
#include "geometry/hausdorff_distance.h"
#include "unfold/triangulate_facets.h"
#include "subfab/core/write_png.h"
#include "support/unfold_test_shapes.h"

namespace subfab {
namespace {

using test::slurp;

TEST(ExportUnfolding, VbitConvention) {
  EXPECT_DOUBLE_EQ(vbit_angle_deg(90), 90);
  EXPECT_STREQ(vbit_side(90), "back");
  EXPECT_DOUBLE_EQ(vbit_angle_deg(135), 45);
  EXPECT_DOUBLE_EQ(vbit_angle_deg(270), 90);
  EXPECT_STREQ(vbit_side(270), "top");
}

TEST(ExportUnfolding, TriangulationKeepsAreaAndHoles) {
  // A box with a square hole through its top facet's middle is not a solid;
  // instead triangulate a single facet with a hole directly.
  PolyMesh ring;
  ring.vertices = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {1, 1, 0}, {3, 1, 0}, {3, 3, 0}, {1, 3, 0}};
  ring.facets.push_back({{{0, 1, 2, 3}, {4, 7, 6, 5}}, 25});
  std::vector<int> owner;
  const Mesh tri = unfold_detail::triangulate_facets(ring, &owner);
  EXPECT_EQ(tri.num_faces(), 8u);
  EXPECT_NEAR(surface_area(tri), 12.0, 1e-12);
  for (std::size_t t = 0; t < tri.num_faces(); ++t) EXPECT_GT(face_unit_normal(tri, t).z(), 0.99);
}

TEST(ExportUnfolding, HausdorffOfKnownOffsets) {
  std::vector<int> owner;
  const Mesh a = unfold_detail::triangulate_facets(test::box(2, 2, 2), &owner);
  Mesh b = a;
  EXPECT_NEAR(detail::hausdorff_distance(a, b, 1000), 0.0, 1e-12);
  for (auto& v : b.vertices) v.z() *= 1.5;  // top moves up by 1
  EXPECT_NEAR(detail::hausdorff_distance(a, b, 1000), 1.0, 1e-9);
}

TEST(ExportUnfolding, PngIsWellFormed) {
  RgbImage img(3, 2);
  img.set(1, 1, 255, 0, 0);
  const auto bytes = encode_png(img);
  ASSERT_GT(bytes.size(), 8u + 25 + 12);
  EXPECT_EQ(bytes[1], 'P');
  EXPECT_EQ(bytes[2], 'N');
  EXPECT_EQ(bytes[3], 'G');
  // IHDR width/height
  EXPECT_EQ(bytes[19], 3);
  EXPECT_EQ(bytes[23], 2);
}

TEST(ExportUnfolding, WritesAllFilesConsistently) {
  const PolyMesh mesh = test::l_prism();
  const Unfolding u = unfold_nets(mesh);
  const auto dir = test::temp_dir();
  const UnfoldSummary summary{.facets_mc = 40, .facets_after_masks = 20, .facets_final = mesh.num_facets(),
                              .nets = u.nets.size(), .hausdorff = 0.25};
  export_unfolding(mesh, u, summary, dir, {.preview_width = 400, .preview_height = 200});
  for (const char* name : {"simplified.obj", "nets.svg", "nets.dxf", "unfold.json", "preview.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;

  // unfold.json: corners in the same order, congruent, folds with V-bit data.
  const auto j = nlohmann::json::parse(slurp(dir / "unfold.json"));
  ASSERT_EQ(j["facets"].size(), mesh.num_facets());
  for (const auto& f : j["facets"]) {
    const auto& v3 = f["vertices3d"];
    const auto& v2 = f["vertices2d"];
    ASSERT_EQ(v3.size(), v2.size());
    for (std::size_t a = 0; a < v3.size(); ++a)
      for (std::size_t b = a + 1; b < v3.size(); ++b) {
        const Vec3 p(v3[a][0], v3[a][1], v3[a][2]), q(v3[b][0], v3[b][1], v3[b][2]);
        const Vec2 r(v2[a][0], v2[a][1]), s(v2[b][0], v2[b][1]);
        EXPECT_NEAR((p - q).norm(), (r - s).norm(), 1e-9);
      }
  }
  EXPECT_EQ(j["folds"].size(), mesh.num_facets() - u.nets.size());
  int reflex = 0;
  for (const auto& f : j["folds"]) {
    const double d = f["dihedral_deg"];
    EXPECT_NEAR(double(f["vbit_deg"]), std::abs(180 - d), 1e-12);
    EXPECT_EQ(f["side"], d < 180 ? "back" : "top");
    reflex += d > 180;
  }
  EXPECT_EQ(j["summary"]["facets_mc"], 40);
  EXPECT_EQ(j["summary"]["facets_after_masks"], 20);
  EXPECT_EQ(j["summary"]["facets_final"], mesh.num_facets());
  EXPECT_EQ(j["summary"]["nets"], u.nets.size());
  EXPECT_DOUBLE_EQ(double(j["summary"]["hausdorff"]), 0.25);

  // simplified.obj reads back as the same closed solid (volume 2 * (6*2 + 2*4) = 40).
  const Mesh back = read_mesh(dir / "simplified.obj");
  EXPECT_NEAR(signed_volume(back), 40.0, 1e-9);

  const std::string svg = slurp(dir / "nets.svg");
  for (const char* id : {"id=\"cut\"", "id=\"fold_top\"", "id=\"fold_back\"", "id=\"facet_ids\""})
    EXPECT_NE(svg.find(id), std::string::npos) << id;
  EXPECT_NE(svg.find("V90.0 back"), std::string::npos);
  const std::string dxf = slurp(dir / "nets.dxf");
  for (const char* layer : {"\nCUT\n", "\nFOLD_BACK\n", "\nLABELS\n", "\nEOF\n"})
    EXPECT_NE(dxf.find(layer), std::string::npos) << layer;
  EXPECT_EQ(slurp(dir / "preview.png").substr(1, 3), "PNG");
}

// unfold.json on a facet with a hole: vertices3d and vertices2d are both the
// outer loop, corner for corner; holes3d and holes2d list the inner loops in
// the same order (and only on facets that have holes); every corner of a
// facet, outer and inner, is congruent between 3D and 2D.
TEST(ExportUnfolding, JsonFacetWithAHoleListsTheSameCornersIn3dAnd2d) {
  const PolyMesh mesh = test::box_on_box();
  ASSERT_EQ(mesh.facets[1].loops.size(), 2u);
  const Unfolding u = unfold_nets(mesh);
  const auto dir = test::temp_dir();
  export_unfolding(mesh, u, UnfoldSummary{.facets_mc = 11, .facets_after_masks = 11, .facets_final = 11,
                                          .nets = u.nets.size(), .hausdorff = 0},
                   dir, {.preview_width = 200, .preview_height = 100});
  const auto j = nlohmann::json::parse(slurp(dir / "unfold.json"));
  ASSERT_EQ(j["facets"].size(), mesh.num_facets());
  std::size_t facets_with_holes = 0;
  for (std::size_t f = 0; f < mesh.num_facets(); ++f) {
    const auto& jf = j["facets"][f];
    EXPECT_EQ(jf["id"], f);
    const Facet& facet = mesh.facets[f];
    EXPECT_EQ(jf.contains("holes3d"), facet.loops.size() > 1) << f;
    EXPECT_EQ(jf.contains("holes2d"), facet.loops.size() > 1) << f;
    // All loops of the facet, 3D and 2D, in the file's order.
    std::vector<Vec3> p3;
    std::vector<Vec2> p2;
    auto take = [&](const nlohmann::json& l3, const nlohmann::json& l2, const std::vector<int>& loop) {
      ASSERT_EQ(l3.size(), loop.size());
      ASSERT_EQ(l2.size(), loop.size());
      for (std::size_t c = 0; c < loop.size(); ++c) {
        const Vec3 q(l3[c][0], l3[c][1], l3[c][2]);
        EXPECT_EQ(q, mesh.vertices[static_cast<std::size_t>(loop[c])]);  // the facet's own loop, same order
        p3.push_back(q);
        p2.emplace_back(l2[c][0], l2[c][1]);
      }
    };
    take(jf["vertices3d"], jf["vertices2d"], facet.loops[0]);
    if (facet.loops.size() > 1) {
      ++facets_with_holes;
      ASSERT_EQ(jf["holes3d"].size(), facet.loops.size() - 1);
      ASSERT_EQ(jf["holes2d"].size(), facet.loops.size() - 1);
      for (std::size_t l = 1; l < facet.loops.size(); ++l) take(jf["holes3d"][l - 1], jf["holes2d"][l - 1], facet.loops[l]);
    }
    for (std::size_t a = 0; a < p3.size(); ++a)
      for (std::size_t b = a + 1; b < p3.size(); ++b)
        EXPECT_NEAR((p3[a] - p3[b]).norm(), (p2[a] - p2[b]).norm(), 1e-9) << f;
    // Not mirrored: the outer loop keeps its counter-clockwise turn in 2D.
    double twice_area = 0;
    for (std::size_t c = 0; c < facet.loops[0].size(); ++c) {
      const Vec2& a = p2[c];
      const Vec2& b = p2[(c + 1) % facet.loops[0].size()];
      twice_area += a.x() * b.y() - a.y() * b.x();
    }
    EXPECT_GT(twice_area, 0) << f;
  }
  EXPECT_EQ(facets_with_holes, 1u);
}

TEST(ExportUnfolding, SheetsSplitNetsAndKeepThemApart) {
  const PolyMesh mesh = test::staircase();
  Unfolding u = unfold_nets(mesh);
  const auto one = layout_sheets(u);
  EXPECT_EQ(one.num_sheets, 1);
  // Nets from different attempts: force several nets by cutting every fold.
  Unfolding pieces = u;
  pieces.nets.clear();
  pieces.folds.clear();
  for (std::size_t f = 0; f < mesh.num_facets(); ++f) {
    pieces.nets.push_back({int(f), {int(f)}, 0.0});
    pieces.net_of_facet[f] = int(f);
    pieces.parent_fold[f] = -1;
  }
  const auto many = layout_sheets(pieces, {.sheet_width = 14, .sheet_height = 10});
  EXPECT_GT(many.num_sheets, 1);
  // every facet lies inside its sheet
  for (std::size_t f = 0; f < mesh.num_facets(); ++f) {
    const double x0 = many.net_sheet[f] * (many.sheet_width + many.gap);
    for (const auto& loop : many.positions[f])
      for (const Vec2& p : loop) {
        EXPECT_GE(p.x(), x0 - 1e-9);
        EXPECT_LE(p.y(), many.sheet_height + 1e-9);
      }
  }
}

}  // namespace
}  // namespace subfab
