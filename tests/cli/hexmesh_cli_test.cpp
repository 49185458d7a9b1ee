// SPDX-License-Identifier: GPL-3.0-or-later
// `subfab hexmesh`: writes the hexahedral mesh, its report and the skeleton;
// bad input (open mesh, malformed skeleton file) exits 2 with the reason.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "subfab/hex/read_skeleton.h"
#include "subfab/mesh/write_mesh.h"
#include "support/hex_test_shapes.h"
#include "support/test_support.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::run_subfab;

TEST(HexmeshCli, WritesMeshReportAndSkeleton) {
  const fs::path dir = test::temp_dir();
  const fs::path input = dir / "capsule.off";
  write_mesh(test::capsule(1.0, 3.0, 32, 8, 24), input);
  const fs::path out = dir / "hex";
  const auto r = run_subfab("hexmesh " + quoted(input) + " -o " + quoted(out) + " --subdivisions 1 --json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* name : {"hexmesh.mesh", "hexmesh.vtk", "hexmesh.json", "skeleton.skel"})
    EXPECT_TRUE(fs::exists(out / name)) << name;
  const auto doc = nlohmann::json::parse(r.output);
  EXPECT_TRUE(doc.at("conforming").get<bool>());
  EXPECT_EQ(doc.at("inverted").get<int>(), 0);
  EXPECT_GT(doc.at("scaled_jacobian").at("min").get<double>(), 0.0);
  EXPECT_EQ(doc.at("hexahedra").get<std::size_t>(), 8 * (doc.at("structure_hexahedra").get<std::size_t>() +
                                                            doc.at("boundary_quads").get<std::size_t>() / 4));
  EXPECT_EQ(nlohmann::json::parse(test::slurp(out / "hexmesh.json")).at("hexahedra"), doc.at("hexahedra"));
  // the skeleton written can be given back
  EXPECT_NO_THROW(read_skeleton(out / "skeleton.skel"));
  const auto again = run_subfab("hexmesh " + quoted(input) + " -o " + quoted(dir / "hex2") + " --subdivisions 1 --skeleton " +
                                quoted(out / "skeleton.skel") + " --quiet");
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(test::slurp(dir / "hex2" / "hexmesh.mesh"), test::slurp(out / "hexmesh.mesh"));
}

// The layer-keeping trial runs with automatic levels on small meshes and is
// reported (tried, kept, the other mesh's numbers); --no-layer-trial and a
// fixed --subdivisions skip it.
TEST(HexmeshCli, LayerTrialIsReportedAndCanBeSkipped) {
  const fs::path dir = test::temp_dir();
  const fs::path input = dir / "capsule.off";
  write_mesh(test::capsule(1.0, 3.0, 32, 8, 24), input);
  const std::string common = " --max-hexes 4000 --no-view --json --quiet";
  const auto tried = run_subfab("hexmesh " + quoted(input) + " -o " + quoted(dir / "a") + common);
  ASSERT_EQ(tried.exit_code, 0) << tried.output;
  const auto t = nlohmann::json::parse(tried.output).at("layer_trial");
  EXPECT_TRUE(t.at("tried").get<bool>());
  EXPECT_GT(t.at("not_kept").at("hexahedra").get<std::size_t>(), 0u);
  EXPECT_GT(t.at("not_kept").at("min_scaled_jacobian").get<double>(), 0.0);
  const auto skipped = run_subfab("hexmesh " + quoted(input) + " -o " + quoted(dir / "b") + common + " --no-layer-trial");
  ASSERT_EQ(skipped.exit_code, 0) << skipped.output;
  EXPECT_FALSE(nlohmann::json::parse(skipped.output).at("layer_trial").at("tried").get<bool>());
  // not kept on the capsule: the same mesh either way
  EXPECT_FALSE(t.at("kept").get<bool>());
  EXPECT_EQ(test::slurp(dir / "a" / "hexmesh.mesh"), test::slurp(dir / "b" / "hexmesh.mesh"));
  const auto fixed = run_subfab("hexmesh " + quoted(input) + " -o " + quoted(dir / "c") +
                                " --subdivisions 1 --no-view --json --quiet");
  ASSERT_EQ(fixed.exit_code, 0) << fixed.output;
  EXPECT_FALSE(nlohmann::json::parse(fixed.output).at("layer_trial").at("tried").get<bool>());
}

TEST(HexmeshCli, BadSkeletonFileExitsTwoWithTheLine) {
  const fs::path dir = test::temp_dir();
  const fs::path input = dir / "capsule.off";
  write_mesh(test::capsule(), input);
  const fs::path skel = dir / "bad.skel";
  std::ofstream(skel) << "ID Cx Cy Cz RADIUS #NEIGHBORS NEIGHBORS_LIST\n2\n0 0 0 0 1 1 1\n1 1 0 0 1 1 5\n";
  const auto r = run_subfab("hexmesh " + quoted(input) + " -o " + quoted(dir / "o") + " --skeleton " + quoted(skel));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.skel:4:"), std::string::npos) << r.output;
  const fs::path nocount = dir / "nocount.skel";
  std::ofstream(nocount) << "ID Cx Cy Cz RADIUS #NEIGHBORS NEIGHBORS_LIST\n0 0 0 0 1 0\n";
  const auto n = run_subfab("hexmesh " + quoted(input) + " -o " + quoted(dir / "o") + " --skeleton " + quoted(nocount));
  EXPECT_EQ(n.exit_code, 2) << n.output;
  EXPECT_NE(n.output.find("nocount.skel:2: missing node count"), std::string::npos) << n.output;
}

// --no-scaling skips resolution control (D.5), which runs by default
// (--scaling says so); on a uniform capsule there is no cone, so the mesh is
// the same.
TEST(HexmeshCli, NoScalingSkipsResolutionControl) {
  const fs::path dir = test::temp_dir();
  const fs::path input = dir / "capsule.off";
  write_mesh(test::capsule(1.0, 3.0, 32, 8, 24), input);
  const auto off = run_subfab("hexmesh " + quoted(input) + " -o " + quoted(dir / "off") +
                              " --subdivisions 1 --no-scaling --no-view --json --quiet");
  ASSERT_EQ(off.exit_code, 0) << off.output;
  const auto doc = nlohmann::json::parse(off.output);
  EXPECT_FALSE(doc.at("resolution_control").at("enabled").get<bool>());
  EXPECT_EQ(doc.at("resolution_control").at("cones_used").get<int>(), 0);
  const auto on = run_subfab("hexmesh " + quoted(input) + " -o " + quoted(dir / "on") +
                             " --subdivisions 1 --scaling --no-view --json --quiet");
  ASSERT_EQ(on.exit_code, 0) << on.output;
  const auto rc = nlohmann::json::parse(on.output).at("resolution_control");
  EXPECT_TRUE(rc.at("enabled").get<bool>());
  EXPECT_EQ(rc.at("cones_found").get<int>(), 0);
  EXPECT_GT(rc.at("ilp").at("variables").get<int>(), 0);
  EXPECT_TRUE(rc.at("ilp").at("solved").get<bool>());
  EXPECT_EQ(test::slurp(dir / "on" / "hexmesh.mesh"), test::slurp(dir / "off" / "hexmesh.mesh"));
  const auto plain = run_subfab("hexmesh " + quoted(input) + " -o " + quoted(dir / "plain") +
                                " --subdivisions 1 --no-view --json --quiet");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_TRUE(nlohmann::json::parse(plain.output).at("resolution_control").at("enabled").get<bool>());
  const auto both = run_subfab("hexmesh " + quoted(input) + " -o " + quoted(dir / "both") + " --scaling --no-scaling");
  EXPECT_NE(both.exit_code, 0) << both.output;
}

TEST(HexmeshCli, OpenMeshExitsTwo) {
  const fs::path dir = test::temp_dir();
  const auto r = run_subfab("hexmesh " + quoted(test::data_path("teapot.obj")) + " -o " + quoted(dir / "o"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

}  // namespace
}  // namespace subfab
