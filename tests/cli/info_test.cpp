// SPDX-License-Identifier: GPL-3.0-or-later
// `subfab info`: exit codes, the one-line cause of unusable input, JSON.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "support/test_support.h"

namespace subfab {
namespace {

using test::quoted;

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

//! Lines of `text` that start with "error".
std::size_t num_error_lines(const std::string& text) {
  std::size_t n = 0, start = 0;
  while (start < text.size()) {
    if (text.compare(start, 5, "error") == 0) ++n;
    const std::size_t end = text.find('\n', start);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return n;
}

const char* kCubeObj =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
    "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\n"
    "f 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";

TEST(InfoCommand, GoodModelExitsZeroWithEveryCheck) {
  const auto r = test::run_subfab("info " + quoted(test::data_path("fandisk.obj")));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const char* word : {"vertices", "faces", "bbox min", "diagonal", "average edge", "area",
                           "volume", "components", "genus", "PASS  self_intersections",
                           "all checks passed"})
    EXPECT_NE(r.output.find(word), std::string::npos) << word << "\n" << r.output;
}

TEST(InfoCommand, BadModelExitsZeroWithProblemsListed) {
  const auto r = test::run_subfab("info " + quoted(test::data_path("teapot.obj")));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("FAIL  boundary_edges          the mesh is not closed: 1036 boundary edges"),
            std::string::npos)
      << r.output;
}

TEST(InfoCommand, CubeJson) {
  const auto dir = test::temp_dir();
  write_file(dir / "cube.obj", kCubeObj);
  const auto r = test::run_subfab("info --json " + quoted(dir / "cube.obj"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["vertices"], 8);
  EXPECT_EQ(j["faces"], 12);
  EXPECT_EQ(j["closed"], true);
  EXPECT_EQ(j["manifold"], true);
  EXPECT_EQ(j["oriented"], true);
  EXPECT_EQ(j["self_intersecting"], false);
  EXPECT_EQ(j["components"], 1);
  EXPECT_EQ(j["genus"], 0);
  EXPECT_EQ(j["bbox"]["min"], nlohmann::json::array({0.0, 0.0, 0.0}));
  EXPECT_EQ(j["bbox"]["max"], nlohmann::json::array({1.0, 1.0, 1.0}));
  EXPECT_DOUBLE_EQ(j["diagonal"].get<double>(), std::sqrt(3.0));
  EXPECT_DOUBLE_EQ(j["average_edge_length"].get<double>(), (12 + 6 * std::sqrt(2.0)) / 18);
  EXPECT_DOUBLE_EQ(j["volume"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["area"].get<double>(), 6.0);
  EXPECT_EQ(j["checks"].size(), 11u);
}

TEST(InfoCommand, InwardCubeJsonSaysSo) {
  const auto dir = test::temp_dir();
  std::string inward = kCubeObj;
  // Reverse every face: "f a b c" -> "f a c b".
  std::string flipped;
  std::istringstream lines(inward);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("f ", 0) == 0) {
      std::istringstream f(line.substr(2));
      std::string a, b, c;
      f >> a >> b >> c;
      line = "f " + a + " " + c + " " + b;
    }
    flipped += line + "\n";
  }
  write_file(dir / "inward.obj", flipped);
  const auto r = test::run_subfab("info --json " + quoted(dir / "inward.obj"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["outward"], false);
  EXPECT_DOUBLE_EQ(j["volume"].get<double>(), -1.0);
}

TEST(InfoCommand, UnusableFilesExitTwoWithOneLineCause) {
  const auto dir = test::temp_dir();
  write_file(dir / "empty.obj", "");
  write_file(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
  for (const auto& path : {dir / "missing.obj", dir / "empty.obj", dir / "nan.obj"}) {
    const auto r = test::run_subfab("info " + quoted(path));
    EXPECT_EQ(r.exit_code, 2) << path << "\n" << r.output;
    EXPECT_EQ(num_error_lines(r.output), 1u) << r.output;
    EXPECT_EQ(r.output.rfind("error: ", 0), 0u) << r.output;
  }
}

TEST(InfoCommand, UsageErrorsExitOne) {
  EXPECT_EQ(test::run_subfab("info").exit_code, 1);
  EXPECT_EQ(test::run_subfab("info --no-such-option " + quoted(test::data_path("cross.off")))
                .exit_code,
            1);
}

}  // namespace
}  // namespace subfab
