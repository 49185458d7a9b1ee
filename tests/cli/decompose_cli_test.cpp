// SPDX-License-Identifier: GPL-3.0-or-later
// `subfab decompose` and `subfab validate` as a user runs them.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "support/block_test_shapes.h"
#include "support/groove_shapes.h"
#include "support/smooth_test_shapes.h"
#include "subfab/mesh/read_mesh.h"
#include "subfab/mesh/write_mesh.h"
#include "subfab/view/read_decomposition.h"
#include "support/test_support.h"

namespace subfab {
namespace {

namespace fs = std::filesystem;
using test::run_subfab;

using test::slurp;

using test::quoted;

TEST(DecomposeCli, DecomposesValidatesAndIsThreadIndependent) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = test::data_path("joint.off");
  auto r1 = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "one") + " --threads 1 --quiet");
  ASSERT_EQ(r1.exit_code, 0) << r1.output;
  auto r2 = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "two") + " --threads 2 --json");
  ASSERT_EQ(r2.exit_code, 0) << r2.output;
  EXPECT_NE(r2.output.find("\"num_blocks\""), std::string::npos);
  // An exact decomposition (no --tolerance, nothing to repair): no fallback.
  EXPECT_NE(r2.output.find("\"tolerance\": 0.0,"), std::string::npos) << r2.output;
  EXPECT_NE(r2.output.find("\"tolerance_fallback\": null"), std::string::npos) << r2.output;
  EXPECT_TRUE(fs::exists(dir / "one" / "blocks" / "block_000.obj"));
  EXPECT_TRUE(fs::exists(dir / "one" / "mill" / "block_000.stl"));
  // Byte-identical outputs apart from the timings.
  for (const auto& entry : fs::recursive_directory_iterator(dir / "one")) {
    if (!entry.is_regular_file()) continue;
    const fs::path rel = fs::relative(entry.path(), dir / "one");
    std::string a = slurp(entry.path()), b = slurp(dir / "two" / rel);
    if (rel == "decomposition.json") {
      a = a.substr(0, a.find("\"timings_s\""));
      b = b.substr(0, b.find("\"timings_s\""));
    }
    EXPECT_EQ(a, b) << rel;
  }
  auto v = run_subfab("validate " + quoted(mesh) + " " + quoted(dir / "one"));
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_NE(v.output.find("all checks passed"), std::string::npos) << v.output;
}

TEST(DecomposeCli, ValidateFailsOnATamperedDecomposition) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = test::data_path("joint.off");
  ASSERT_EQ(run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir) + " --quiet").exit_code, 0);
  ASSERT_TRUE(fs::exists(dir / "blocks" / "block_001.obj"));  // joint.off needs two blocks
  EXPECT_EQ(run_subfab("validate " + quoted(mesh) + " " + quoted(dir) + " --quiet").exit_code, 0);
  // Point block 0 at block 1's files: a duplicate (overlap) and a gap.
  std::string tampered = slurp(dir / "decomposition.json");
  const auto first = tampered.find("\"blocks/block_000.obj\"");
  ASSERT_NE(first, std::string::npos);
  tampered.replace(first, 22, "\"blocks/block_001.obj\"");
  std::ofstream(dir / "decomposition.json", std::ios::binary) << tampered;
  auto v = run_subfab("validate " + quoted(mesh) + " " + quoted(dir));
  EXPECT_EQ(v.exit_code, 3) << v.output;
  EXPECT_NE(v.output.find("FAIL"), std::string::npos);
}

TEST(DecomposeCli, RefusesAnOpenMeshAndBadOptions) {
  const fs::path dir = test::temp_dir();
  auto open = run_subfab("decompose " + quoted(test::data_path("teapot.obj")) + " -o " + quoted(dir));
  EXPECT_EQ(open.exit_code, 2) << open.output;
  auto missing = run_subfab("decompose " + quoted(dir / "nope.obj") + " -o " + quoted(dir));
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  auto machine = run_subfab("decompose " + quoted(test::data_path("cross.off")) + " -o " + quoted(dir) +
                            " --machine 1,2");
  EXPECT_EQ(machine.exit_code, 1) << machine.output;
  auto height = run_subfab("decompose " + quoted(test::data_path("cross.off")) + " -o " + quoted(dir) +
                           " --max-height -3");
  EXPECT_EQ(height.exit_code, 1) << height.output;
  auto overhang = run_subfab("decompose " + quoted(test::data_path("cross.off")) + " -o " + quoted(dir) +
                             " --max-overhang 50");
  EXPECT_EQ(overhang.exit_code, 1) << overhang.output;
  EXPECT_NE(overhang.output.find("--max-overhang"), std::string::npos) << overhang.output;
  auto rounds = run_subfab("decompose " + quoted(test::data_path("cross.off")) + " -o " + quoted(dir) +
                           " --tolerance 1e-3 --tolerance-rounds 0");
  EXPECT_EQ(rounds.exit_code, 1) << rounds.output;
  EXPECT_NE(rounds.output.find("--tolerance-rounds"), std::string::npos) << rounds.output;
  auto no_dir = run_subfab("validate " + quoted(test::data_path("cross.off")) + " " + quoted(dir / "absent"));
  EXPECT_EQ(no_dir.exit_code, 2) << no_dir.output;
  auto help = run_subfab("decompose --help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* option : {"--max-height", "--max-height-abs", "--machine", "--no-orient", "--grid-factor",
                             "--exact", "--max-deviation", "--max-overhang", "--tolerance-rounds", "--threads", "--json", "--quiet"})
    EXPECT_NE(help.output.find(option), std::string::npos) << option;
}

//! A thin wedge (30-degree apex) whose sharp edge runs along (1, 1, 1): no
//! axis sees both faces at that edge, in the input frame (the six exact
//! corner positions below, outward faces).
void write_oblique_wedge(const fs::path& path) {
  std::ofstream out(path);
  out << "v 0.1 0.2 0.3\n"
         "v 0.8886751345948128 -0.3773502691896257 0.08867513459481285\n"
         "v 0.6773502691896257 -0.5886751345948129 0.5113248654051872\n"
         "v 0.9660254037844388 1.0660254037844388 1.1660254037844389\n"
         "v 1.7547005383792516 0.4886751345948131 0.9547005383792517\n"
         "v 1.5433756729740646 0.2773502691896259 1.377350269189626\n";
  for (const char* f : {"1 2 3", "4 6 5", "1 5 2", "1 4 5", "2 6 3", "2 5 6", "3 4 1", "3 6 4"}) out << "f " << f << "\n";
}

TEST(DecomposeCli, InfeasibleFeaturesAreRepairedOrRefusedWithExact) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = dir / "wedge.obj";
  write_oblique_wedge(mesh);
  // --exact: refused with the list.
  auto exact = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "exact") + " --no-orient --exact");
  EXPECT_EQ(exact.exit_code, 3) << exact.output;
  EXPECT_NE(exact.output.find("crease edge(s)"), std::string::npos) << exact.output;
  EXPECT_EQ(exact.output.find("repairing them"), std::string::npos) << exact.output;
  EXPECT_FALSE(fs::exists(dir / "exact" / "decomposition.json"));
  // Default: the repair runs (said on stderr); a cap it cannot meet is exit 3
  // and says how to relax it.
  auto tight = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "tight") +
                          " --no-orient --max-deviation 1e-7");
  EXPECT_EQ(tight.exit_code, 3) << tight.output;
  EXPECT_NE(tight.output.find("repairing them by local smoothing"), std::string::npos) << tight.output;
  EXPECT_NE(tight.output.find("--max-deviation"), std::string::npos) << tight.output;
  EXPECT_FALSE(fs::exists(dir / "tight" / "decomposition.json"));
}

TEST(DecomposeCli, MaxOverhangIsRecordedSaidAndValidatedAgainst) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = dir / "barrel.obj";
  write_mesh(test::barrel_solid(1.0, 1.0, 5.0), mesh);  // lower faces lean 5 deg past vertical
  auto d = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "out") +
                      " --no-orient --max-overhang 10 --json");
  ASSERT_EQ(d.exit_code, 0) << d.output;
  const auto summary = nlohmann::json::parse(d.output.substr(d.output.find('{')));
  EXPECT_EQ(summary["num_blocks"], 1);
  EXPECT_EQ(summary["max_overhang_allowed_deg"], 10.0);
  EXPECT_NEAR(summary["max_overhang_deg"].get<double>(), 5.0, 1e-6);
  EXPECT_NE(d.output.find("OVERHANGS ALLOWED"), std::string::npos) << d.output;
  const auto doc = nlohmann::json::parse(slurp(dir / "out" / "decomposition.json"));
  EXPECT_EQ(doc["parameters"]["max_overhang_deg"], 10.0);
  EXPECT_NEAR(doc["blocks"][0]["max_overhang_deg"].get<double>(), 5.0, 1e-6);
  // validate takes the recorded allowance and says so; --max-overhang 0 checks exactness.
  auto v = run_subfab("validate " + quoted(mesh) + " " + quoted(dir / "out"));
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_NE(v.output.find("allows faces leaning up to 10 deg"), std::string::npos) << v.output;
  auto strict = run_subfab("validate " + quoted(mesh) + " " + quoted(dir / "out") + " --max-overhang 0");
  EXPECT_EQ(strict.exit_code, 3) << strict.output;
  EXPECT_NE(strict.output.find("5.00 deg past vertical"), std::string::npos) << strict.output;
  // Exact by default: two blocks, nothing said about overhangs.
  auto e = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "exact") + " --no-orient");
  ASSERT_EQ(e.exit_code, 0) << e.output;
  EXPECT_EQ(e.output.find("OVERHANGS"), std::string::npos) << e.output;
  EXPECT_TRUE(fs::exists(dir / "exact" / "blocks" / "block_001.obj"));
  auto exact_check = run_subfab("validate " + quoted(mesh) + " " + quoted(dir / "exact") + " --max-overhang 0");
  EXPECT_EQ(exact_check.exit_code, 0) << exact_check.output;
}

TEST(DecomposeCli, ValidateChecksARecordedRepairedInput) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = test::data_path("joint.off");
  // --no-orient: joint is drawn in its own frame, where the default would snap
  // its CAD noise within the file's rounding (a recorded snap, not wanted here)
  ASSERT_EQ(run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir) + " --no-orient --quiet").exit_code, 0);
  // Feasible: no repair record, no repaired mesh.
  std::string json = slurp(dir / "decomposition.json");
  const std::string none = "\"repair\": null";
  ASSERT_NE(json.find(none), std::string::npos) << json;
  EXPECT_FALSE(fs::exists(dir / "input_repaired.obj"));
  // Record a "repair" whose mesh is the input itself (deviation 0): validate
  // must check against the named mesh and say so.
  fs::copy_file(mesh, dir / "input_repaired.off");
  json.replace(json.find(none), none.size(),
               "\"repair\": {\"mesh\": \"input_repaired.off\", \"num_features\": 2, \"max_deviation\": 0.0, "
               "\"max_deviation_fraction\": 0.0, \"mean_deviation\": 0.0}");
  std::ofstream(dir / "decomposition.json", std::ios::binary) << json;
  auto v = run_subfab("validate " + quoted(mesh) + " " + quoted(dir));
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_NE(v.output.find("REPAIRED input"), std::string::npos) << v.output;
  EXPECT_NE(v.output.find("all checks passed"), std::string::npos) << v.output;
  // A repaired mesh that is not MESH's repair (bounding boxes too far apart) is refused.
  fs::copy_file(test::data_path("cross.off"), dir / "input_repaired.off", fs::copy_options::overwrite_existing);
  EXPECT_EQ(run_subfab("validate " + quoted(mesh) + " " + quoted(dir) + " --quiet").exit_code, 2);
}

// --smooth-passes, --smooth-lambda and --smooth-mu reach the smoother
// (recorded in input.smoothing): more passes move the vertices farther, up
// to the cap; without --smooth they are usage errors.
TEST(DecomposeCli, SmoothPassesAndFactorsSetTheSmoothingStrength) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = dir / "bumped.obj";
  write_mesh(test::bumped_cube(8, 0.2), mesh);
  const auto smoothed_by = [&](int passes) {
    const fs::path out = dir / ("p" + std::to_string(passes));
    const auto r = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(out) + " --no-orient --smooth=0.05 " +
                              "--smooth-passes " + std::to_string(passes) + " --quiet --no-view --threads 1");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const auto doc = nlohmann::json::parse(slurp(out / "decomposition.json"));
    const auto& s = doc.at("input").at("smoothing");
    EXPECT_EQ(s.at("passes").get<int>(), passes);
    EXPECT_LE(s.at("smoothed_max_deviation_fraction").get<double>(), 0.05 * (1 + 1e-9));
    return s.at("smoothed_max_deviation_fraction").get<double>();
  };
  const double few = smoothed_by(3);
  const double many = smoothed_by(60);
  EXPECT_GT(many, 1.2 * few);  // measured: 0.034 x diagonal after 3 passes, 0.044 after 60
  const auto usage = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "u") + " --smooth-passes 5");
  EXPECT_EQ(usage.exit_code, 1) << usage.output;
  EXPECT_NE(usage.output.find("--smooth"), std::string::npos) << usage.output;
  // The filter's factors (the authors' tool used 0.89 / -0.9): recorded; out of range is a usage error.
  const fs::path filter = dir / "filter";
  const auto f = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(filter) + " --no-orient --smooth=0.05 " +
                            "--smooth-passes 3 --smooth-lambda 0.89 --smooth-mu -0.9 --quiet --no-view --threads 1");
  ASSERT_EQ(f.exit_code, 0) << f.output;
  const auto fdoc = nlohmann::json::parse(slurp(filter / "decomposition.json"));
  EXPECT_EQ(fdoc.at("input").at("smoothing").at("lambda").get<double>(), 0.89);
  EXPECT_EQ(fdoc.at("input").at("smoothing").at("mu").get<double>(), -0.9);
  // other factors, another smoothing (3 passes: 0.0324 x diagonal against the default's 0.0335)
  EXPECT_NE(fdoc.at("input").at("smoothing").at("smoothed_max_deviation_fraction").get<double>(), few);
  const auto bad = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "b") +
                              " --smooth --smooth-lambda 1.5 --quiet --no-view");
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_NE(bad.output.find("lambda must be in (0, 1)"), std::string::npos) << bad.output;
}

// Regression: `--tolerance-abs D` alone was bounded by the unset --tolerance
// (0, the smaller wins) and gave exact blocks.
TEST(DecomposeCli, ToleranceAbsAloneIsTheTolerance) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = dir / "grooved.obj";
  write_mesh(test::voxel_mesh(test::grooved_box_cells()), mesh);  // groove 1 deep round a 10-cube
  const auto blocks_within = [&](const std::string& option, const std::string& name) {
    const fs::path out = dir / name;
    const auto r = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(out) + " --no-orient " + option +
                              " --quiet --no-view --threads 1");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const auto doc = nlohmann::json::parse(slurp(out / "decomposition.json"));
    return std::pair{doc.at("blocks").size(), doc.at("parameters").at("tolerance").get<double>()};
  };
  const auto [exact_blocks, zero] = blocks_within("--tolerance 0", "exact");
  EXPECT_EQ(zero, 0.0);
  const auto [abs_blocks, abs] = blocks_within("--tolerance-abs 2.5", "abs");
  EXPECT_EQ(abs, 2.5);
  EXPECT_LT(abs_blocks, exact_blocks);  // the groove (1 deep) filled within 2.5
  const auto [both_blocks, both] = blocks_within("--tolerance-abs 2.5 --tolerance 0.01", "both");
  EXPECT_NEAR(both, 0.01 * std::sqrt(300.0), 1e-12);  // the smaller wins
  EXPECT_EQ(both_blocks, exact_blocks);               // 0.17 < the groove's depth
}

// --smooth on a CAD part: the smoothing rounds its edges and tilts its flat
// faces off the axes, so the smoothed model has creases no block covers while
// the input has none (joint.off: 2 exact blocks). The error says the
// smoothing made them and what to do; where the input has such features too
// (the diagonal spike), it does not claim so.
TEST(DecomposeCli, SmoothOnACadPartSaysTheSmoothingMadeTheFeatures) {
  const fs::path dir = test::temp_dir();
  const fs::path joint = test::data_path("joint.off");
  const auto plain = run_subfab("decompose " + quoted(joint) + " -o " + quoted(dir / "plain") + " --no-view --threads 1");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  const auto r = run_subfab("decompose " + quoted(joint) + " -o " + quoted(dir / "smoothed") +
                            " --smooth=0.01 --smooth-passes 5 --exact --no-view --threads 1");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("the smoothing made features no height-field block can cover"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("without --smooth"), std::string::npos) << r.output;
  const auto spike = run_subfab("decompose " + quoted(test::data_path("regression/cube_tiny_diagonal_spike.obj")) +
                                " -o " + quoted(dir / "spike") +
                                " --smooth=0.0001 --smooth-passes 2 --exact --no-view --threads 1");
  EXPECT_EQ(spike.exit_code, 3) << spike.output;
  EXPECT_EQ(spike.output.find("the smoothing made"), std::string::npos) << spike.output;
}

// --smooth with --tolerance: the smoothed model decomposed within the
// tolerance, recorded as such; validate checks the blocks against it.
TEST(DecomposeCli, SmoothWithAToleranceDecomposesTheSmoothedModelWithinIt) {
  const fs::path dir = test::temp_dir();
  const fs::path mesh = dir / "leaning.obj";
  write_mesh(test::bumped_cube(12, 0.25, 0.2), mesh);
  const fs::path out = dir / "out";
  const auto r = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(out) +
                            " --no-orient --smooth=0.01 --smooth-passes 20 --tolerance 0.05 --no-view --threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("SMOOTHED, THEN WITHIN A TOLERANCE"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "input_smoothed.obj"));
  EXPECT_FALSE(fs::exists(out / "input_restored.obj"));
  const auto doc = nlohmann::json::parse(slurp(out / "decomposition.json"));
  const auto& s = doc.at("input").at("smoothing");
  EXPECT_FALSE(s.at("restored").get<bool>());
  EXPECT_EQ(doc.at("input").at("decomposed_mesh").get<std::string>(), "input_smoothed.obj");
  EXPECT_NEAR(doc.at("parameters").at("tolerance_fraction").get<double>(), 0.05, 1e-12);
  // what a later view of the folder shows: the smoothed model, so labelled
  const DecompositionFolder folder = read_decomposition(out);
  EXPECT_EQ(folder.decomposed_mesh, "input_smoothed.obj");
  EXPECT_STREQ(folder.model_label, "smoothed input");
  const std::optional<Mesh> model = read_decomposed_model(folder);
  ASSERT_TRUE(model.has_value());
  EXPECT_EQ(model->vertices, read_mesh(out / "input_smoothed.obj").vertices);
  EXPECT_NE(model->vertices, read_mesh(mesh).vertices);
  EXPECT_LE(s.at("max_deviation_fraction").get<double>(), 0.01 * (1 + 1e-12));
  const double total = s.at("total_deviation_bound_fraction").get<double>();
  EXPECT_GT(total, s.at("max_deviation_fraction").get<double>());
  EXPECT_LE(total, 0.06 * (1 + 1e-12));
  const auto v = run_subfab("validate " + quoted(mesh) + " " + quoted(out));
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_NE(v.output.find("SMOOTHED"), std::string::npos) << v.output;
  EXPECT_NE(v.output.find("then decomposed within --tolerance"), std::string::npos) << v.output;
  // against the input itself: within the smoothing's bound plus the tolerance (the deviations add up)
  const auto a = run_subfab("validate " + quoted(mesh) + " " + quoted(out) + " --against-input --json --quiet");
  EXPECT_EQ(a.exit_code, 0) << a.output;
  const auto aj = nlohmann::json::parse(a.output.substr(a.output.find('{')));
  EXPECT_TRUE(aj.at("against_input").get<bool>());
  EXPECT_NEAR(aj.at("tolerance_fraction").get<double>(), 0.05 + s.at("max_deviation_fraction").get<double>(), 1e-9);
  EXPECT_GT(aj.at("deviation").at("max_fraction").get<double>(), 0.0);
  // slivers judged at the tolerance the blocks were made within, as decompose judged them
  EXPECT_NEAR(aj.at("thickness").at("sliver_threshold_fraction").get<double>(), 0.05, 1e-9);
  // an overhang allowance does not combine with it
  const auto m = run_subfab("decompose " + quoted(mesh) + " -o " + quoted(dir / "m") +
                            " --smooth --tolerance 0.05 --max-overhang 5 --quiet --no-view");
  EXPECT_EQ(m.exit_code, 1) << m.output;
  EXPECT_NE(m.output.find("--max-overhang"), std::string::npos) << m.output;
}

}  // namespace
}  // namespace subfab
