// SPDX-License-Identifier: GPL-3.0-or-later
// view.html: the page's structure, its embedded data, and its errors.
#include "subfab/view/write_view_html.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "decomposition_folder.h"
#include "subfab/core/error.h"
#include "subfab/view/write_decomposition_view.h"
#include "support/test_support.h"
#include "view/encode_base64.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;

TEST(EncodeBase64, KnownVectors) {
  const auto b64 = [](const std::string& s) {
    return detail::encode_base64(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
  };
  EXPECT_EQ(b64(""), "");
  EXPECT_EQ(b64("M"), "TQ==");
  EXPECT_EQ(b64("Ma"), "TWE=");
  EXPECT_EQ(b64("Man"), "TWFu");
  EXPECT_EQ(b64("subfab!"), "c3ViZmFiIQ==");
  EXPECT_EQ(detail::base64_float32({1.0f}), "AACAPw==");  // 00 00 80 3f, little-endian
  EXPECT_EQ(detail::base64_uint32({1u, 256u}), "AQAAAAABAAA=");
}

//! The JSON embedded in a page.
nlohmann::json scene_of(const std::string& page) {
  const std::string open = "<script id=\"subfab-scene\" type=\"application/json\">";
  const auto a = page.find(open);
  const auto b = page.find("</script>", a);
  if (a == std::string::npos || b == std::string::npos) return nullptr;
  return nlohmann::json::parse(page.substr(a + open.size(), b - a - open.size()));
}

TEST(WriteViewHtml, SelfContainedPageWithTheScene) {
  ViewScene scene;
  scene.title = "a <test> & \"title\"";
  ViewObject box;
  box.name = "block </script> 0";
  box.mesh = test::make_box_mesh({0, 0, 0}, {1, 2, 3});
  box.color = {1, 2, 3};
  box.info = {{"Number", "0"}};
  scene.objects.push_back(box);
  ViewObject facet;
  facet.name = "facet";
  facet.polygons.push_back({{{{0, 0}, {1, 0}, {0, 1}}}, {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}});
  scene.objects.push_back(facet);
  const std::string page = view_html(scene, "var THREE = {};");
  EXPECT_NE(page.find("Content-Security-Policy\" content=\"default-src 'none'"), std::string::npos);
  EXPECT_NE(page.find("a &lt;test&gt; &amp; &quot;title&quot;"), std::string::npos);
  EXPECT_EQ(page.find("<script src"), std::string::npos);
  EXPECT_EQ(page.find("<link"), std::string::npos);
  EXPECT_NE(page.find("window.subfabStatus"), std::string::npos);  // the viewer is in
  const nlohmann::json j = scene_of(page);  // "</script>" in a name did not end the block
  ASSERT_TRUE(j.is_object());
  ASSERT_EQ(j["objects"].size(), 2u);
  EXPECT_EQ(j["objects"][0]["name"], "block </script> 0");
  EXPECT_EQ(j["objects"][0]["color"], nlohmann::json({1, 2, 3}));
  // 8 vertices x 3 float32 = 96 bytes = 128 base64 characters; 36 uint32 indices.
  EXPECT_EQ(j["objects"][0]["positions"].get<std::string>().size(), 128u);
  EXPECT_EQ(j["objects"][0]["indices"].get<std::string>().size(), (36u * 4 + 2) / 3 * 4);
  EXPECT_EQ(j["objects"][1]["polygons"][0]["loops"], nlohmann::json({3}));
  // Same scene, same bytes.
  EXPECT_EQ(page, view_html(scene, "var THREE = {};"));
}

TEST(WriteViewHtml, MissingThreeJsIsAClearError) {
  try {
    read_three_js({.three_js_path = "/nonexistent/three.min.js"});
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("libjs-three"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--no-view"), std::string::npos) << e.what();
  }
}

TEST(WriteDecompositionView, BlocksColouredByDirectionWithTheModelAsGhost) {
  const fs::path dir = test::temp_dir();
  write_decomposition_folder(dir, test::cup_and_key());
  const DecompositionFolder folder = read_decomposition(dir);
  ASSERT_EQ(folder.blocks.size(), 6u);
  EXPECT_EQ(folder.blocks[5].axis, "+z");
  EXPECT_EQ(folder.blocks[0].stock_size, Vec3(3, 3, 1));
  const Mesh model = test::make_box_mesh({0, 0, 0}, {3, 3, 3});
  const ViewScene scene = decomposition_scene(folder, &model);
  ASSERT_EQ(scene.objects.size(), 7u);
  EXPECT_EQ(scene.objects[0].style, ViewStyle::Ghost);
  for (std::size_t i = 0; i < 6; ++i) {
    const ViewObject& o = scene.objects[i + 1];
    EXPECT_EQ(o.name, "block " + std::to_string(i));
    // Same hue as the direction colour: the two equal channels stay equal.
    const Rgb base = direction_color(folder.blocks[i].axis);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (base[a] == base[b]) {
          EXPECT_EQ(o.color[a], o.color[b]);
        }
  }
  EXPECT_EQ(scene.legend.size(), 6u);
  // The key, in the middle of the cup's top, explodes upwards.
  EXPECT_GT(scene.objects[6].explode_offset.z(), 0);
  EXPECT_NEAR(scene.objects[6].explode_offset.x(), 0, 1e-12);
}

TEST(WriteDecompositionView, WritesTheFileOrExplainsWhyNot) {
  const fs::path dir = test::temp_dir();
  write_decomposition_folder(dir, test::cup_and_key(), (dir / "missing.obj").string());
  if (!fs::exists(kDefaultThreeJsPath) && !std::getenv("SUBFAB_THREE_JS")) GTEST_SKIP() << "libjs-three not installed";
  write_decomposition_view(dir);  // the model is missing: blocks only
  const nlohmann::json j = scene_of(test::slurp(dir / "view.html"));
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j["objects"].size(), 6u);
  EXPECT_THROW(write_decomposition_view(dir / "nothing"), IoError);
}

}  // namespace
}  // namespace subfab
