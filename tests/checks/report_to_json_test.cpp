// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/checks/report_to_json.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/test_shapes.h"

namespace subfab {
namespace {

TEST(ReportToJson, CubeFieldsAndValues) {
  const nlohmann::json j = report_to_json(analyze_mesh(test::cube(Vec3::Zero(), 2.0)));
  for (const char* key : {"vertices", "faces", "closed", "manifold", "oriented",
                          "self_intersecting", "components", "genus", "bbox", "diagonal",
                          "average_edge_length", "volume", "area", "checks"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["vertices"], 8);
  EXPECT_EQ(j["faces"], 12);
  EXPECT_EQ(j["closed"], true);
  EXPECT_EQ(j["self_intersecting"], false);
  EXPECT_EQ(j["genus"], 0);
  EXPECT_EQ(j["bbox"]["max"], nlohmann::json::array({2.0, 2.0, 2.0}));
  EXPECT_DOUBLE_EQ(j["volume"].get<double>(), 8.0);
  EXPECT_DOUBLE_EQ(j["area"].get<double>(), 24.0);
  ASSERT_EQ(j["checks"].size(), 11u);
  for (const auto& check : j["checks"]) EXPECT_EQ(check["status"], "passed") << check["name"];
}

TEST(ReportToJson, UnknownValuesAreNull) {
  Mesh m = test::cube();
  m.faces.pop_back();
  const nlohmann::json j = report_to_json(analyze_mesh(m));
  EXPECT_EQ(j["closed"], false);
  EXPECT_TRUE(j["genus"].is_null());
  EXPECT_TRUE(j["volume"].is_null());
  const auto& boundary = j["checks"][4];
  EXPECT_EQ(boundary["name"], "boundary_edges");
  EXPECT_EQ(boundary["status"], "failed");
  EXPECT_EQ(boundary["count"], 3);
  EXPECT_EQ(boundary["groups"], 1);
  EXPECT_EQ(boundary["element"], "vertex");
}

}  // namespace
}  // namespace subfab
