// SPDX-License-Identifier: GPL-3.0-or-later
//! `subfab validate MESH OUTDIR`: checks a decomposition written by
//! `subfab decompose` against its input (the seven checks of
//! validate_decomposition.h). Prints a table per check; exit 0 when all
//! pass, 3 when one fails, 2 when the input or the folder cannot be read.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "command.h"
#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "subfab/decompose/validate_decomposition.h"
#include "subfab/mesh/read_mesh.h"

namespace subfab::cli {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

struct ValidateArgs {
  std::string mesh;
  std::string outdir;
  CommonOptions common;
};

Vec3 json_vec(const Json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3) throw IoError(what + ": expected an array of 3 numbers");
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

//! Reads decomposition.json and the block files it lists.
std::vector<ValidationBlock> read_decomposition(const fs::path& outdir, ValidationLimits& limits) {
  const fs::path path = outdir / "decomposition.json";
  std::ifstream in(path);
  if (!in) throw IoError(path.string() + ": cannot open (is this a folder written by subfab decompose?)");
  Json doc;
  try {
    doc = Json::parse(in);
    if (doc.at("format").get<std::string>() != "subfab.decomposition")
      throw IoError(path.string() + ": not a subfab.decomposition file");
    const Json& p = doc.at("parameters");
    if (p.contains("max_height") && !p["max_height"].is_null()) limits.max_height = p["max_height"].get<double>();
    if (p.contains("machine") && !p["machine"].is_null()) limits.machine = json_vec(p["machine"], "parameters.machine");
    std::vector<ValidationBlock> blocks;
    for (const Json& b : doc.at("blocks")) {
      ValidationBlock vb;
      vb.mesh = read_mesh(outdir / b.at("mesh").get<std::string>());
      vb.direction = json_vec(b.at("direction"), "direction");
      const fs::path machine = outdir / b.at("machine_mesh").get<std::string>();
      if (fs::exists(machine)) vb.machine_mesh = read_mesh(machine);
      const Json& m = b.at("machine_transform");
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) vb.machine_transform(r, c) = m.at(static_cast<std::size_t>(r)).at(static_cast<std::size_t>(c)).get<double>();
      blocks.push_back(std::move(vb));
    }
    return blocks;
  } catch (const Json::exception& e) {
    throw IoError(path.string() + ": malformed: " + e.what());
  }
}

int run_validate(const ValidateArgs& args) {
  ThreadLimit threads(static_cast<std::size_t>(args.common.threads));
  const Mesh input = read_mesh(args.mesh);  // IoError / InvalidMeshError: exit 2
  ValidationOptions options;
  const std::vector<ValidationBlock> blocks = read_decomposition(args.outdir, options.limits);
  ConsoleProgress progress(std::cerr, args.common.quiet, stderr_is_terminal());
  options.progress = &progress;
  const ValidationReport report = validate_decomposition(input, blocks, options);

  if (args.common.json) {
    nlohmann::ordered_json j;
    j["input"] = args.mesh;
    j["decomposition"] = args.outdir;
    j["num_blocks"] = blocks.size();
    j["passed"] = report.passed();
    nlohmann::ordered_json checks = nlohmann::ordered_json::array();
    for (const CheckReport& c : report.checks)
      checks.push_back({{"name", c.name},
                        {"passed", c.passed},
                        {"summary", c.summary},
                        {"num_failures", c.num_failures},
                        {"failures", c.failures}});
    j["checks"] = checks;
    std::cout << j.dump(2) << "\n";
  } else {
    std::ostringstream out;
    out << "validate " << args.outdir << " against " << args.mesh << " (" << blocks.size() << " blocks)\n";
    int k = 1;
    for (const CheckReport& c : report.checks) {
      out << "  " << k++ << ". " << (c.passed ? "PASS" : "FAIL") << "  " << std::left << std::setw(62) << c.name
          << c.summary << "\n";
      for (const std::string& f : c.failures) out << "           " << f << "\n";
      if (c.num_failures > c.failures.size())
        out << "           ... and " << (c.num_failures - c.failures.size()) << " more\n";
    }
    out << (report.passed() ? "all checks passed\n" : "validation FAILED\n");
    std::cout << out.str();
  }
  return report.passed() ? kExitOk : kExitFailed;
}

const RegisterCommand kRegisterValidate({"validate", 30, [](CLI::App& app) {
  auto args = std::make_shared<ValidateArgs>();
  CLI::App* sub = app.add_subcommand(
      "validate",
      "Check a decomposition written by `subfab decompose` against its input: (1) every block a closed, "
      "oriented 2-manifold with positive volume; (2) a height field along its direction (faces with "
      "n.d < -1e-3 only on the base); (3) no overlaps (exact, <= 1e-6 of the smaller block); (4) inside "
      "the input (exact, <= 1e-6 of the block outside); (5) the input surface covered (20000+ samples "
      "within 1e-5 x diagonal of a block); (6) height and machine limits; (7) machine meshes are the "
      "blocks moved rigidly. Exit 0 if all pass, 3 if one fails, 2 if the files cannot be read.");
  sub->add_option("MESH", args->mesh, "The input mesh that was decomposed")->required();
  sub->add_option("OUTDIR", args->outdir, "Folder written by subfab decompose")->required();
  add_common_options(*sub, args->common);
  return std::pair<CLI::App*, std::function<int()>>{sub, [args] { return run_validate(*args); }};
}});

}  // namespace
}  // namespace subfab::cli
