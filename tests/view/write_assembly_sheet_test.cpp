// SPDX-License-Identifier: GPL-3.0-or-later
// assembly.html: units, mill.json's facts, the gluing order, the pictures.
#include "subfab/view/write_assembly_sheet.h"

#include <gtest/gtest.h>

#include <fstream>

#include "decomposition_folder.h"
#include "subfab/core/error.h"
#include "support/test_support.h"
#include "view/render_picture.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(WriteAssemblySheet, ModelUnitsWithoutAScale) {
  const fs::path dir = test::temp_dir();
  write_decomposition_folder(dir, test::cup_and_key());
  const AssemblySheet sheet = write_assembly_sheet(dir);
  EXPECT_TRUE(fs::exists(dir / "assembly.html"));
  EXPECT_EQ(sheet.mm_per_unit, 0);
  EXPECT_LT(sheet.total_time_s, 0);
  EXPECT_NE(sheet.html.find("Sizes in model units"), std::string::npos);
  EXPECT_NE(sheet.html.find("3 &times; 3 &times; 1 model units"), std::string::npos);  // the base
  EXPECT_EQ(count(sheet.html, "<div class=\"step\">"), 6u);
  EXPECT_EQ(count(sheet.html, "src=\"data:image/png;base64,"), 12u);
  // The base first; the key from above (small blocks leave first, so the
  // order is: base, the x walls, the key, the y walls).
  EXPECT_NE(sheet.html.find("Step 1: block 0</h3><table><tr><th>Glue</th><td>first block"), std::string::npos);
  EXPECT_NE(sheet.html.find("Step 4: block 5</h3><table><tr><th>Glue</th><td>slide in from the +z side"),
            std::string::npos);
  EXPECT_EQ(sheet.html.find("http:"), std::string::npos);
  EXPECT_EQ(sheet.html.find("https:"), std::string::npos);
}

TEST(WriteAssemblySheet, SizeScalesToMillimetres) {
  const fs::path dir = test::temp_dir();
  write_decomposition_folder(dir, test::cup_and_key());
  AssemblySheetOptions options;
  options.size_mm = 150;  // the cup is 3 units wide
  const AssemblySheet sheet = write_assembly_sheet(dir, options);
  EXPECT_DOUBLE_EQ(sheet.mm_per_unit, 50);
  EXPECT_NE(sheet.html.find("150 &times; 150 &times; 50 mm"), std::string::npos);
  options.mm_per_unit = -1;
  EXPECT_THROW(write_assembly_sheet(dir, options), InvalidArgumentError);
}

TEST(WriteAssemblySheet, ReadsMillJson) {
  const fs::path dir = test::temp_dir();
  write_decomposition_folder(dir, test::cup_and_key());
  fs::create_directories(dir / "gcode");
  std::ofstream(dir / "gcode" / "mill.json") << R"({"format": "subfab.mill", "scale_mm_per_unit": 10,
    "blocks": [{"id": 5, "gcode": "block_005.nc", "stock_mm": [14, 14, 24], "time_s": 3725},
               {"index": 0, "stock_mm": [34, 34, 14], "time_s": 60}]})";
  const MillInfo mill = read_mill_info(dir / "gcode");
  EXPECT_EQ(mill.mm_per_unit, 10);
  ASSERT_EQ(mill.blocks.size(), 2u);
  EXPECT_EQ(mill.blocks.at(5).gcode, "block_005.nc");
  AssemblySheetOptions options;
  options.mill_dir = dir / "gcode";
  const AssemblySheet sheet = write_assembly_sheet(dir, options);
  EXPECT_EQ(sheet.mm_per_unit, 10);
  EXPECT_DOUBLE_EQ(sheet.total_time_s, 3785);
  EXPECT_NE(sheet.html.find("14 &times; 14 &times; 24 mm"), std::string::npos);  // mill.json's stock, with margin
  EXPECT_NE(sheet.html.find("1 h 2 min"), std::string::npos);
  EXPECT_NE(sheet.html.find("block_005.nc"), std::string::npos);
  EXPECT_NE(sheet.html.find("10 &times; 30 &times; 20 mm"), std::string::npos);  // block 1, not in mill.json: its box
  EXPECT_THROW(read_mill_info(dir / "nothing"), IoError);
  std::ofstream(dir / "gcode" / "mill.json") << "{\"blocks\": 3}";
  EXPECT_THROW(read_mill_info(dir / "gcode"), IoError);
}

TEST(RenderPicture, PngOfTheLayersWithTheNewPartVisible) {
  // A box hidden under a lid from the default view (which looks down): the
  // assembly picture of the box looks from below.
  const Mesh lid = test::make_box_mesh({-1, 1, -1}, {2, 1.2, 2});
  const Mesh box = test::make_box_mesh({0, 0, 0}, {1, 1, 1});
  detail::PictureView view;
  view.frame = bounding_box(lid);
  view.frame.extend(Vec3(0, 0, 0));
  view.width = view.height = 64;
  const std::string plain = detail::render_picture({{&lid, {200, 200, 200}}, {&box, {215, 48, 48}}}, view);
  EXPECT_EQ(plain.rfind("data:image/png;base64,iVBORw0KGgo", 0), 0u);  // the PNG signature
  detail::AssemblyPictures pictures(view, {200, 200, 200});
  const std::string first = pictures.add(lid, {215, 48, 48});
  EXPECT_EQ(first, detail::render_picture({{&lid, {215, 48, 48}}}, view));  // the unmirrored view shows the lid best
  const std::string second = pictures.add(box, {215, 48, 48});
  EXPECT_NE(second, plain);  // not the view from above, where the lid hides the box
  view.towards_eye.y() = -view.towards_eye.y();
  EXPECT_EQ(second, detail::render_picture({{&lid, {200, 200, 200}}, {&box, {215, 48, 48}}}, view));
}

}  // namespace
}  // namespace subfab
