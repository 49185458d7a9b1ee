// SPDX-License-Identifier: GPL-3.0-or-later
// `subfab hexmesh` writes preview.png and view.html (cells coloured by
// scaled Jacobian), or no view.html with --no-view (removing an earlier one).
#include <gtest/gtest.h>

#include <cstdlib>

#include "subfab/mesh/write_mesh.h"
#include "support/hex_test_shapes.h"
#include "support/test_support.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::run_subfab;

TEST(HexmeshViewCli, WritesPreviewAndViewOrNoViewWithNoView) {
  const fs::path dir = test::temp_dir();
  const fs::path input = dir / "capsule.off";
  write_mesh(test::capsule(1.0, 3.0, 32, 8, 24), input);
  const fs::path out = dir / "hex";
  const std::string command = "hexmesh " + quoted(input) + " -o " + quoted(out) + " --subdivisions 1 --quiet";
  auto r = run_subfab(command);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(test::slurp(out / "preview.png").substr(0, 4), "\x89PNG");
  if (!std::getenv("SUBFAB_THREE_JS") && !fs::exists("/usr/share/javascript/three/three.min.js"))
    GTEST_SKIP() << "libjs-three not installed";
  const std::string page = test::slurp(out / "view.html");
  EXPECT_NE(page.find("subfab hexmesh"), std::string::npos);
  EXPECT_NE(page.find("\"hex\":{"), std::string::npos);
  r = run_subfab(command + " --no-view");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(out / "view.html"));  // the earlier run's page went
  EXPECT_TRUE(fs::exists(out / "preview.png"));
  // Without three.js: a warning, no page, the mesh still written (exit 0).
  setenv("SUBFAB_THREE_JS", "/nonexistent/three.min.js", 1);
  r = run_subfab("hexmesh " + quoted(input) + " -o " + quoted(out) + " --subdivisions 1");
  unsetenv("SUBFAB_THREE_JS");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("view.html not written"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "view.html"));
}

}  // namespace
}  // namespace subfab
