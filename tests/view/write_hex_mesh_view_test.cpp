// SPDX-License-Identifier: GPL-3.0-or-later
// The hexahedral mesh's view.html scene and preview.png: cells coloured by
// their scaled Jacobian's histogram bin, face neighbours, the tubular
// structure beside the mesh, and the picture's colours.
#include "subfab/view/write_hex_mesh_view.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <map>
#include <nlohmann/json.hpp>

#include "subfab/core/error.h"
#include "support/test_support.h"

namespace subfab {
namespace {

//! A row of n unit cubes along x (VTK corner order), from x = x0.
HexCellArrays cube_row(int n, double x0 = 0) {
  HexCellArrays a;
  for (int i = 0; i <= n; ++i)
    for (auto [y, z] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) a.points.emplace_back(x0 + i, y, z);
  // Points of slice i: 4i + (0: y0z0, 1: y1z0, 2: y1z1, 3: y0z1). Bottom quad 0-1-2-3 (z = 0) must
  // turn towards the top quad (z = 1): corners (x0,y0,0) (x1,y0,0) (x1,y1,0) (x0,y1,0).
  for (int i = 0; i < n; ++i) {
    const int a0 = 4 * i, b0 = 4 * (i + 1);
    a.cells.push_back({a0 + 0, b0 + 0, b0 + 1, a0 + 1, a0 + 3, b0 + 3, b0 + 2, a0 + 2});
  }
  return a;
}

TEST(HexFaceNeighbors, ARowOfCubesSharesOneFaceBetweenNeighbours) {
  const auto n = hex_face_neighbors(cube_row(3).cells);
  ASSERT_EQ(n.size(), 3u);
  int shared = 0;
  for (int c = 0; c < 3; ++c)
    for (int f = 0; f < 6; ++f)
      if (n[std::size_t(c)][std::size_t(f)] >= 0) {
        ++shared;
        EXPECT_EQ(std::abs(n[std::size_t(c)][std::size_t(f)] - c), 1);
      }
  EXPECT_EQ(shared, 4);  // 0-1 and 1-2, each seen from both sides
  EXPECT_EQ(n[0][3], 1);  // face {1, 2, 6, 5}: the x = 1 side
  EXPECT_EQ(n[1][5], 0);  // face {3, 0, 4, 7}: the x = 1 side of cell 1
}

TEST(QualityColor, OneColourPerHistogramBin) {
  EXPECT_EQ(quality_color(-0.3), (Rgb{255, 0, 255}));
  EXPECT_EQ(quality_color(0.0), (Rgb{255, 0, 255}));  // degenerate counts as inverted, as in hexmesh.json
  EXPECT_EQ(quality_color(0.05), (Rgb{255, 0, 0}));
  EXPECT_EQ(quality_color(0.1), (Rgb{255, 0, 0}));    // (0, .1]
  EXPECT_EQ(quality_color(0.95), (Rgb{0, 85, 255}));  // hue 220
  EXPECT_EQ(quality_color(1.0), (Rgb{0, 85, 255}));
  EXPECT_NE(quality_color(0.11), quality_color(0.1));
  const auto legend = quality_legend();
  ASSERT_EQ(legend.size(), 11u);
  for (std::size_t b = 1; b < legend.size(); ++b) EXPECT_NE(legend[b].color, legend[b - 1].color) << b;
  EXPECT_EQ(legend[10].label, "0.9-1");
}

HexMeshView three_cubes() {
  HexMeshView v;
  v.mesh = cube_row(3);
  v.scaled_jacobian = {0.95, 0.55, 0.05};
  v.structure = cube_row(1);
  v.input_name = "row.off";
  return v;
}

TEST(HexMeshScene, CellsWithTheirColoursValuesAndNeighboursAndTheStructureBeside) {
  const HexMeshView v = three_cubes();
  const ViewScene scene = hex_mesh_scene(v);
  ASSERT_EQ(scene.objects.size(), 2u);  // no input given: no ghost
  const ViewHexCells& cells = scene.objects[0].hex;
  ASSERT_EQ(cells.cells.size(), 3u);
  EXPECT_EQ(cells.colors[0], quality_color(0.95));
  EXPECT_EQ(cells.colors[2], quality_color(0.05));
  EXPECT_EQ(cells.values, v.scaled_jacobian);
  EXPECT_EQ(cells.neighbors, hex_face_neighbors(v.mesh.cells));
  EXPECT_NE(scene.subtitle.find("min 0.05"), std::string::npos) << scene.subtitle;
  // The structure (a unit cube) lies right of the mesh on the screen, not overlapping it.
  const Vec3 right = Vec3::UnitY().cross(scene.towards_eye.normalized()).normalized();
  double mesh_right = -1e300, core_left = 1e300;
  for (const Vec3& p : v.mesh.points) mesh_right = std::max(mesh_right, p.dot(right));
  const Mesh& core = scene.objects[1].mesh;
  EXPECT_EQ(core.faces.size(), 12u);  // its six faces
  for (const Vec3& p : core.vertices) core_left = std::min(core_left, p.dot(right));
  EXPECT_GT(core_left, mesh_right);
  // In the page: the cells as base64 arrays (3 x 8 uint32 = 96 bytes = 128 characters).
  const std::string page = view_html(scene, "var THREE = {};");
  EXPECT_NE(page.find("\"cells\":\""), std::string::npos);
  EXPECT_NE(page.find("Scaled Jacobian"), std::string::npos);
  EXPECT_NE(page.find("id=\"cut\""), std::string::npos);
}

TEST(HexMeshScene, MismatchedArraysAreRefused) {
  HexMeshView v = three_cubes();
  v.scaled_jacobian.pop_back();
  EXPECT_THROW(hex_mesh_scene(v), InvalidArgumentError);
  v = three_cubes();
  v.mesh.cells[1][3] = 99;
  EXPECT_THROW(hex_mesh_preview_png(v), InvalidArgumentError);
}

//! Pixels of a PNG that encode_png_rgb wrote (8-bit RGB, filter 0 rows).
std::vector<Rgb> decode_png(const std::vector<std::uint8_t>& png, int& width, int& height) {
  const auto be32 = [&](std::size_t at) {
    return (std::uint32_t(png[at]) << 24) | (std::uint32_t(png[at + 1]) << 16) | (std::uint32_t(png[at + 2]) << 8) |
           std::uint32_t(png[at + 3]);
  };
  std::vector<std::uint8_t> packed;
  for (std::size_t at = 8; at + 8 <= png.size();) {
    const std::uint32_t size = be32(at);
    const std::string type(png.begin() + std::ptrdiff_t(at) + 4, png.begin() + std::ptrdiff_t(at) + 8);
    if (type == "IHDR") width = int(be32(at + 8)), height = int(be32(at + 12));
    if (type == "IDAT") packed.insert(packed.end(), png.begin() + std::ptrdiff_t(at) + 8, png.begin() + std::ptrdiff_t(at + 8 + size));
    at += 12 + size;
  }
  std::vector<std::uint8_t> rows(std::size_t(width * 3 + 1) * std::size_t(height));
  uLongf size = rows.size();
  EXPECT_EQ(uncompress(rows.data(), &size, packed.data(), packed.size()), Z_OK);
  std::vector<Rgb> out;
  for (int y = 0; y < height; ++y) {
    const std::size_t row = std::size_t(y) * std::size_t(width * 3 + 1);
    EXPECT_EQ(rows[row], 0);
    for (int x = 0; x < width; ++x) {
      const std::size_t at = row + 1 + 3 * std::size_t(x);
      out.push_back({rows[at], rows[at + 1], rows[at + 2]});
    }
  }
  return out;
}

//! The colour's hue in degrees, or -1 for a grey (saturation under 0.3).
int hue_of(const Rgb& c) {
  const int hi = std::max({c[0], c[1], c[2]}), lo = std::min({c[0], c[1], c[2]});
  if (hi == 0 || (hi - lo) < 0.3 * hi) return -1;
  double h;
  const double d = hi - lo;
  if (hi == c[0]) h = 60 * std::fmod((c[1] - c[2]) / d + 6, 6.0);
  else if (hi == c[1]) h = 60 * ((c[2] - c[0]) / d + 2);
  else h = 60 * ((c[0] - c[1]) / d + 4);
  return int(std::lround(h)) % 360;
}

TEST(HexMeshPreview, TheBoundaryInItsQualityColoursAndTheStructureInGrey) {
  const HexMeshView v = three_cubes();
  int w = 0, h = 0;
  const std::vector<Rgb> pixels = decode_png(hex_mesh_preview_png(v, {.width = 300, .height = 160}), w, h);
  ASSERT_EQ(w, 300);
  ASSERT_EQ(h, 160);
  std::map<int, int> hues;  // hue -> pixels
  int white = 0, structure_grey = 0;
  for (const Rgb& c : pixels) {
    if (c == Rgb{255, 255, 255}) ++white;
    else if (hue_of(c) < 0 && c[2] > c[0] && c[0] > 70) ++structure_grey;  // shaded (170, 170, 178), not the outline
    else if (hue_of(c) >= 0) ++hues[hue_of(c)];
  }
  EXPECT_GT(white, w * h / 3);  // background
  EXPECT_GT(structure_grey, 300);
  // Each cube in its bin's hue (shading scales all channels: the hue stays): 220 (0.95), 122 (0.55), 0 (0.05).
  const auto near = [&](int hue) {
    int n = 0;
    for (auto [k, count] : hues)
      if (std::min(std::abs(k - hue), 360 - std::abs(k - hue)) <= 4) n += count;
    return n;
  };
  const int blue = near(220), green = near(122), red = near(0);
  EXPECT_GT(blue, 300);
  EXPECT_GT(green, 300);
  EXPECT_GT(red, 300);
  int other = 0;
  for (auto [k, count] : hues) other += count;
  EXPECT_EQ(other, blue + green + red);  // nothing else saturated (no magenta: nothing inverted)
}

TEST(HexMeshPreview, WritesAPngFile) {
  const auto path = test::temp_dir() / "preview.png";
  write_hex_mesh_preview(three_cubes(), path);
  const std::string bytes = test::slurp(path);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  EXPECT_THROW(write_hex_mesh_preview(three_cubes(), test::temp_dir() / "no" / "such" / "preview.png"), IoError);
}

}  // namespace
}  // namespace subfab
