// SPDX-License-Identifier: GPL-3.0-or-later
//! `subfab validate MESH OUTDIR`: checks a decomposition written by
//! `subfab decompose` against its input (the checks of
//! validate_decomposition.h). Prints a table per check; exit 0 when all
//! pass, 3 when one fails, 2 when the input or the folder cannot be read.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "command.h"
#include "subfab/core/error.h"
#include "subfab/geometry/axis.h"
#include "subfab/validate/validate_decomposition.h"
#include "subfab/mesh/read_mesh.h"

namespace subfab::cli {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

struct ValidateArgs {
  std::string mesh;
  std::string outdir;
  std::optional<double> max_overhang;  // --max-overhang: overrides the recorded allowance
  std::optional<double> tolerance;     // --tolerance: overrides the recorded tolerance (fraction of the diagonal)
  bool against_input = false;          // --against-input: checks 4, 5, 10 against MESH, not what was decomposed
  CommonOptions common;
};

Vec3 json_vec(const Json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3) throw IoError(what + ": expected an array of 3 numbers");
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

//! A repair recorded in decomposition.json ("input"."repair": thin features;
//! "input"."mesh_repair": `decompose --repair`), if any.
struct RecordedRepair {
  std::string mesh;  // OUTDIR-relative path of the repaired input
  double max_deviation = 0, max_deviation_fraction = 0, mean_deviation = 0;
  std::string what;  // what it changed, for the note
  bool smoothed_only = false;  // --smooth with --tolerance: the smoothed model, details not restored
  double error = 0;  // error bound of max_deviation (model units; 0 when not recorded or a bound)
};

//! The recorded error bound of a measured deviation ("hausdorff_error"; 0 when none).
double recorded_error(const Json& r) { return r.contains("hausdorff_error") ? r["hausdorff_error"].get<double>() : 0.0; }

struct RecordedRepairs {
  std::optional<RecordedRepair> features;  // thin-feature repair (of the mesh below, when there is one)
  std::optional<RecordedRepair> mesh;      // --repair: the solid made of the input file
  std::optional<RecordedRepair> restored;  // --smooth: the smoothed model with its details restored
  //! The one the blocks decompose (the last applied).
  const RecordedRepair* decomposed() const {
    return restored ? &*restored : features ? &*features : mesh ? &*mesh : nullptr;
  }
};

//! Reads decomposition.json and the block files it lists.
//! Decompose's frame as recorded (check 10 measures there when every block has its frame block).
struct RecordedFrame {
  std::optional<Eigen::Matrix3d> rotation;  // "rotation" (set when "frame" is there)
  double snap_tolerance = 1e-9;             // "frame"."snap_tolerance"
};

std::vector<ValidationBlock> read_decomposition(const fs::path& outdir, ValidationLimits& limits,
                                                RecordedRepairs& repairs, double& max_overhang_deg,
                                                double& tolerance_fraction, RecordedFrame& frame) {
  const fs::path path = outdir / "decomposition.json";
  std::ifstream in(path);
  if (!in) throw IoError(path.string() + ": cannot open (is this a folder written by subfab decompose?)");
  Json doc;
  try {
    doc = Json::parse(in);
    if (doc.at("format").get<std::string>() != "subfab.decomposition")
      throw IoError(path.string() + ": not a subfab.decomposition file");
    const Json& input_json = doc.at("input");
    if (input_json.contains("repair") && !input_json["repair"].is_null()) {
      const Json& r = input_json["repair"];
      repairs.features = RecordedRepair{
          r.at("mesh").get<std::string>(), r.at("max_deviation").get<double>(),
          r.at("max_deviation_fraction").get<double>(), r.at("mean_deviation").get<double>(),
          r.contains("precision_snap") && !r["precision_snap"].is_null() && r.at("num_features").get<int>() == 0
              ? "coordinates snapped within the file's own rounding (" +
                    std::to_string(r["precision_snap"].at("num_vertices_moved").get<std::size_t>()) +
                    " vertices moved)"
              : std::to_string(r.at("num_features").get<int>()) + " infeasible features smoothed"};
      repairs.features->error = recorded_error(r);
    }
    if (input_json.contains("mesh_repair") && !input_json["mesh_repair"].is_null()) {
      const Json& r = input_json["mesh_repair"];
      repairs.mesh = RecordedRepair{r.at("mesh").get<std::string>(), r.at("max_deviation").get<double>(),
                                    r.at("max_deviation_fraction").get<double>(),
                                    r.at("mean_deviation").get<double>(),
                                    "repaired with --repair: " + r.at("applied_steps").get<std::string>()};
      repairs.mesh->error = recorded_error(r);
    }
    if (input_json.contains("smoothing") && !input_json["smoothing"].is_null()) {
      const Json& r = input_json["smoothing"];
      const bool restored = !r.contains("restored") || r["restored"].get<bool>();
      repairs.restored = RecordedRepair{
          r.at("mesh").get<std::string>(), r.at("max_deviation").get<double>(),
          r.at("max_deviation_fraction").get<double>(), r.at("mean_deviation").get<double>(),
          "smoothed (cap " + std::to_string(r.at("cap_fraction").get<double>()) + " x diagonal)" +
              (restored ? " and details restored with --smooth" : " with --smooth, then decomposed within --tolerance"),
          !restored};
      if (restored) repairs.restored->error = recorded_error(r);  // else max_deviation is a bound
    }
    const Json& p = doc.at("parameters");
    if (p.contains("max_height") && !p["max_height"].is_null()) limits.max_height = p["max_height"].get<double>();
    if (p.contains("machine") && !p["machine"].is_null()) limits.machine = json_vec(p["machine"], "parameters.machine");
    max_overhang_deg = p.contains("max_overhang_deg") ? p["max_overhang_deg"].get<double>() : 0.0;
    tolerance_fraction = p.contains("tolerance_fraction") ? p["tolerance_fraction"].get<double>() : 0.0;
    if (doc.contains("frame") && doc["frame"].is_object()) {
      const Json& r = doc.at("rotation");
      Eigen::Matrix3d rot;
      for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c) rot(i, c) = r.at(static_cast<std::size_t>(i)).at(static_cast<std::size_t>(c)).get<double>();
      frame.rotation = rot;
      frame.snap_tolerance = doc["frame"].at("snap_tolerance").get<double>();
    }
    std::vector<ValidationBlock> blocks;
    for (const Json& b : doc.at("blocks")) {
      ValidationBlock vb;
      vb.mesh = read_mesh(outdir / b.at("mesh").get<std::string>());
      vb.direction = json_vec(b.at("direction"), "direction");
      const fs::path machine = outdir / b.at("machine_mesh").get<std::string>();
      if (fs::exists(machine)) vb.machine_mesh = read_mesh(machine);
      if (b.contains("frame_mesh")) vb.frame_mesh = read_mesh(outdir / b["frame_mesh"].get<std::string>());
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

std::string sci(double x, int digits = 2) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*e", digits - 1, x);
  return buf;
}

std::string percent(double part, double whole) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g%%", whole > 0 ? 100.0 * part / whole : 0.0);
  return buf;
}

std::string block_label(std::size_t i) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "block %03zu", i);
  return buf;
}

//! The milled-shape lines of the text report (informational, issue 17).
void print_milled(std::ostream& out, const MilledShapesReport& r, double diagonal) {
  const double d = std::max(diagonal, 1e-300);
  const std::size_t n = r.blocks.size(), exact = r.num_exact();
  if (exact == n) {
    out << "  milled shapes (informational): every block is an exact height field, its milled shape is the block "
           "(filled 0, deviation 0)\n";
    return;
  }
  out << "  milled shapes (informational): " << (n - exact) << " of " << n
      << " blocks overhang; what a 3-axis machine makes of them (distances within " << sci(r.hausdorff_error / d)
      << " x diagonal):\n";
  double filled = 0.0, volume = 0.0, worst = -1.0;
  std::size_t worst_block = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const MilledShapeMeasures& m = r.blocks[i];
    volume += m.block_volume;
    filled += m.filled_volume;
    if (m.exact) continue;
    if (m.deviation > worst) {
      worst = m.deviation;
      worst_block = i;
    }
    out << "    " << block_label(i) << ": ";
    if (!m.error.empty()) out << m.error << "; ";
    out << "filled " << sci(m.filled_volume) << " (" << percent(m.filled_volume, m.block_volume)
        << " of the block), deviation " << sci(m.deviation / d) << " x diagonal (undercut depth "
        << sci(m.deviation_to_block / d) << "), outside the input " << sci(m.outside_volume) << " ("
        << percent(m.outside_volume, m.block_volume) << " of the block) up to " << sci(m.outside_distance / d)
        << " x diagonal\n";
  }
  for (const MilledCollision& c : r.collisions)
    out << "    " << block_label(c.a) << " and " << block_label(c.b) << ": milled shapes collide, overlap "
        << sci(c.volume) << "\n";
  out << "  milled shapes: max deviation " << sci(std::max(worst, 0.0) / d) << " x diagonal (" << block_label(worst_block)
      << "), filled " << sci(filled) << " in total (" << percent(filled, volume) << " of the blocks' volume), "
      << r.collisions.size() << " collisions (" << r.num_pairs_checked << " pairs checked)\n";
}

//! Every block's thickness (check 9) for the text report, several per line.
void print_thickness(std::ostream& out, const ValidationReport& r, double diagonal) {
  const double d = std::max(diagonal, 1e-300);
  if (r.slivers.empty()) return;
  std::size_t thinnest = 0;
  for (std::size_t i = 0; i < r.slivers.size(); ++i)
    if (r.slivers[i].thickness.thickness < r.slivers[thinnest].thickness.thickness) thinnest = i;
  out << "  block thickness (mean chord along the thinnest frame axis, x diagonal; * = below "
      << sci(r.sliver_thickness / d) << ", ! = sliver):";
  for (std::size_t i = 0; i < r.slivers.size(); ++i) {
    const SliverMeasure& m = r.slivers[i];
    if (i % 8 == 0) out << "\n   ";
    char buf[64];
    std::snprintf(buf, sizeof buf, " %03zu %.2e%s", i, m.thickness.thickness / d, m.sliver ? "!" : m.measured ? "*" : " ");
    out << buf;
  }
  out << "\n  thinnest block: " << block_label(thinnest) << ", " << sci(r.slivers[thinnest].thickness.thickness / d, 3)
      << " x diagonal (" << r.slivers[thinnest].thickness.thickness << " model units)\n";
  for (std::size_t i = 0; i < r.slivers.size(); ++i) {
    const SliverMeasure& m = r.slivers[i];
    if (!m.measured) continue;
    out << "    " << block_label(i) << ": " << sci(m.thickness.thickness / d) << " x diagonal thick; on "
        << m.num_chords << " lines along its thinnest axis the block is " << sci(m.block_chord / d)
        << ", the model " << sci(m.model_chord / d) << (m.sliver ? " (sliver)" : " (the model is that thin)")
        << "\n";
  }
}

//! The "thickness" object of --json (check 9).
nlohmann::ordered_json thickness_json(const ValidationReport& r, double diagonal) {
  const double d = std::max(diagonal, 1e-300);
  nlohmann::ordered_json blocks = nlohmann::ordered_json::array();
  double thinnest = r.slivers.empty() ? 0.0 : std::numeric_limits<double>::infinity();
  std::size_t num_slivers = 0;
  for (std::size_t i = 0; i < r.slivers.size(); ++i) {
    const SliverMeasure& m = r.slivers[i];
    thinnest = std::min(thinnest, m.thickness.thickness);
    num_slivers += m.sliver ? 1 : 0;
    nlohmann::ordered_json b = {{"id", i},
                                {"thickness", m.thickness.thickness},
                                {"thickness_fraction", m.thickness.thickness / d},
                                {"axis", {m.thickness.axis.x(), m.thickness.axis.y(), m.thickness.axis.z()}},
                                {"sliver", m.sliver}};
    if (m.measured) {
      b["num_chords"] = m.num_chords;
      b["block_chord"] = m.block_chord;
      b["model_chord"] = m.model_chord;
    }
    blocks.push_back(b);
  }
  return {{"min_thickness", thinnest},
          {"min_thickness_fraction", thinnest / d},
          {"sliver_threshold", r.sliver_thickness},
          {"sliver_threshold_fraction", r.sliver_thickness / d},
          {"num_slivers", num_slivers},
          {"blocks", blocks}};
}

//! The "milled_shapes" object of --json.
nlohmann::ordered_json milled_json(const MilledShapesReport& r, double diagonal) {
  const double d = std::max(diagonal, 1e-300);
  nlohmann::ordered_json blocks = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < r.blocks.size(); ++i) {
    const MilledShapeMeasures& m = r.blocks[i];
    blocks.push_back({{"id", i},
                      {"exact", m.exact},
                      {"num_faces", m.num_faces},
                      {"block_volume", m.block_volume},
                      {"volume", m.volume},
                      {"filled_volume", m.filled_volume},
                      {"deviation", m.deviation},
                      {"deviation_fraction", m.deviation / d},
                      {"deviation_to_block", m.deviation_to_block},
                      {"deviation_to_block_fraction", m.deviation_to_block / d},
                      {"outside_volume", m.outside_volume},
                      {"outside_distance", m.outside_distance},
                      {"outside_distance_fraction", m.outside_distance / d},
                      {"error", m.error.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(m.error)}});
  }
  nlohmann::ordered_json collisions = nlohmann::ordered_json::array();
  for (const MilledCollision& c : r.collisions) collisions.push_back({{"a", c.a}, {"b", c.b}, {"volume", c.volume}});
  return {{"num_exact", r.num_exact()},
          {"hausdorff_error", r.hausdorff_error},
          {"max_deviation", r.max_deviation()},
          {"max_deviation_fraction", r.max_deviation() / d},
          {"total_filled_volume", r.total_filled_volume()},
          {"num_collisions", r.collisions.size()},
          {"num_pairs_checked", r.num_pairs_checked},
          {"blocks", blocks},
          {"collisions", collisions}};
}

int run_validate(const ValidateArgs& args) {
  Mesh input = read_mesh(args.mesh);  // IoError / InvalidMeshError: exit 2
  ValidationOptions options;
  RecordedRepairs repairs;
  double recorded_overhang = 0.0, recorded_tolerance = 0.0;
  RecordedFrame frame;
  const std::vector<ValidationBlock> blocks =
      read_decomposition(args.outdir, options.limits, repairs, recorded_overhang, recorded_tolerance, frame);
  options.frame_rotation = frame.rotation;
  options.frame_snap_tolerance = frame.snap_tolerance;
  const RecordedRepair* repair = args.against_input ? nullptr : repairs.decomposed();
  // Fractions are of the INPUT's diagonal, as decompose records them (a
  // repaired or smoothed model's is a little different).
  const double diagonal = bounding_box(input).diagonal();
  // --against-input: what the blocks decompose lies within its recorded
  // deviations of MESH (they add up), the blocks within the tolerance of it
  double recorded_deviation = 0.0;
  for (const auto* r : {repairs.mesh ? &*repairs.mesh : nullptr, repairs.features ? &*repairs.features : nullptr,
                        repairs.restored ? &*repairs.restored : nullptr})
    if (r) recorded_deviation += r->max_deviation + r->error;
  const double tolerance_fraction =
      args.tolerance ? *args.tolerance
                     : recorded_tolerance + (args.against_input ? recorded_deviation / std::max(diagonal, 1e-300) : 0.0);
  const double overhang = args.max_overhang ? *args.max_overhang : recorded_overhang;
  try {
    options.normal_tolerance = height_field_normal_tolerance(overhang);
  } catch (const InvalidArgumentError& e) {
    throw IoError(args.outdir + "/decomposition.json: parameters.max_overhang_deg: " + e.what());
  }
  ConsoleProgress progress(std::cerr, args.common.quiet, stderr_is_terminal());
  options.progress = &progress;
  std::string overhang_note;
  if (overhang > 0) {
    std::ostringstream note;
    note << "NOTE: check 2 allows faces leaning up to " << overhang << " deg past vertical ("
         << (args.max_overhang ? "--max-overhang" : "decomposed with --max-overhang, as recorded")
         << "): such blocks are not exact height fields; pass --max-overhang 0 to check exactness";
    overhang_note = note.str();
    if (!args.common.quiet) progress.warn(overhang_note);
  }
  std::string repair_note;
  if (repair) {
    // The blocks decompose the repaired input: checks 4 (inside) and 5
    // (coverage) are run against it (decompose recorded its deviation).
    const Mesh original = std::move(input);
    input = read_mesh(fs::path(args.outdir) / repair->mesh);
    std::ostringstream note;
    note << "NOTE: the decomposition is of the " << (!repairs.restored                    ? "REPAIRED"
             : repairs.restored->smoothed_only ? "SMOOTHED"
                                                  : "RESTORED (smoothed, details put back)")
         << " input " << (fs::path(args.outdir) / repair->mesh).string()
         << " (";
    double recorded = 0;  // the deviations add up (triangle inequality)
    for (const auto* r : {repairs.mesh ? &*repairs.mesh : nullptr, repairs.features ? &*repairs.features : nullptr,
                          repairs.restored ? &*repairs.restored : nullptr}) {
      if (!r) continue;
      if (recorded > 0) note << "; then ";
      note << r->what << ", recorded Hausdorff deviation " << r->max_deviation << " = " << r->max_deviation_fraction
           << " of the diagonal, mean " << r->mean_deviation;
      recorded += r->max_deviation + 1e-300;
    }
    note << "; from " << args.mesh << "); checks 4 (inside) and 5 (coverage) use it";
    // Sanity check that it is the repaired version of MESH: the bounding
    // boxes differ by at most the recorded deviation (+ its error bound).
    const BoundingBox a = bounding_box(original), b = bounding_box(input);
    const double slack = recorded + 2e-5 * a.diagonal();
    if (!((a.min - b.min).cwiseAbs().maxCoeff() <= slack && (a.max - b.max).cwiseAbs().maxCoeff() <= slack))
      throw IoError(note.str() + "; but its bounding box differs from " + args.mesh +
                    "'s by more than the recorded deviation: is this the mesh that was decomposed?");
    repair_note = note.str();
    if (!args.common.quiet) progress.warn(repair_note);
  }
  options.tolerance = tolerance_fraction * diagonal;
  // --against-input: slivers are judged at the tolerance the blocks were made within, as decompose judged them
  if (args.against_input && !args.tolerance) options.sliver_tolerance = recorded_tolerance * diagonal;
  std::string tolerance_note;
  if (tolerance_fraction > 0) {
    std::ostringstream note;
    note << "NOTE: decomposition within a tolerance of " << tolerance_fraction << " x diagonal = "
         << options.tolerance << " ("
         << (args.tolerance         ? "--tolerance"
             : args.against_input ? "--against-input: the recorded tolerance plus the recorded deviations of what "
                                    "the blocks decompose from " + args.mesh
                                  : "as recorded")
         << "): blocks may stick out of the input (check 4), samples within it count as covered (check 5), "
            "and check 10 measures the deviation of the model made";
    tolerance_note = note.str();
    if (!args.common.quiet) progress.warn(tolerance_note);
  }
  const ValidationReport report = validate_decomposition(input, blocks, options);

  if (args.common.json) {
    nlohmann::ordered_json j;
    j["input"] = args.mesh;
    j["decomposition"] = args.outdir;
    j["num_blocks"] = blocks.size();
    j["passed"] = report.passed();
    j["max_overhang_deg"] = overhang;
    j["tolerance_fraction"] = tolerance_fraction;
    j["against_input"] = args.against_input;
    if (options.tolerance > 0)
      j["deviation"] = {{"num_sticking_out", report.num_filled},
                        {"num_bounded_by_parts", report.num_bounded_by_parts},
                        {"to_input", report.deviation_to_input},
                        {"from_input", report.deviation_from_input},
                        {"max_fraction", std::max(report.deviation_to_input, report.deviation_from_input) / diagonal},
                        {"error_bound", report.deviation_error},
                        {"measured_in_frame", report.measured_in_frame},
                        {"frame_rounding", report.frame_rounding}};
    if (repair)
      j["repaired_input"] = {{"mesh", (fs::path(args.outdir) / repair->mesh).string()},
                             {"max_deviation", repair->max_deviation},
                             {"max_deviation_fraction", repair->max_deviation_fraction},
                             {"mean_deviation", repair->mean_deviation}};
    else
      j["repaired_input"] = nullptr;
    nlohmann::ordered_json checks = nlohmann::ordered_json::array();
    for (const CheckReport& c : report.checks)
      checks.push_back({{"name", c.name},
                        {"passed", c.passed},
                        {"summary", c.summary},
                        {"num_failures", c.num_failures},
                        {"failures", c.failures}});
    j["checks"] = checks;
    j["thickness"] = thickness_json(report, diagonal);
    j["milled_shapes"] = milled_json(report.milled, diagonal);
    std::cout << j.dump(2) << "\n";
  } else {
    std::ostringstream out;
    out << "validate " << args.outdir << " against " << args.mesh << " (" << blocks.size() << " blocks)\n";
    if (repair) out << "  " << repair_note << "\n";
    if (overhang > 0) out << "  " << overhang_note << "\n";
    if (!tolerance_note.empty()) out << "  " << tolerance_note << "\n";
    int k = 1;
    for (const CheckReport& c : report.checks) {
      out << "  " << k++ << ". " << (c.passed ? "PASS" : "FAIL") << "  " << std::left << std::setw(62) << c.name
          << (c.name.size() >= 62 ? "  " : "") << c.summary << "\n";
      for (const std::string& f : c.failures) out << "           " << f << "\n";
      if (c.num_failures > c.failures.size())
        out << "           ... and " << (c.num_failures - c.failures.size()) << " more\n";
    }
    print_thickness(out, report, diagonal);
    print_milled(out, report.milled, diagonal);
    out << (report.passed() ? "all checks passed\n" : "validation FAILED\n");
    std::cout << out.str();
  }
  return report.passed() ? kExitOk : kExitFailed;
}

void add_validate_options(CLI::App& sub, ValidateArgs& args) {
  sub.add_option("MESH", args.mesh, "The input mesh that was decomposed")->required();
  sub.add_option("OUTDIR", args.outdir, "Folder written by subfab decompose")->required();
  sub.add_option("--max-overhang", args.max_overhang,
                 "Overhang allowance of check 2, degrees past vertical (default: the one decompose recorded "
                 "in decomposition.json, 0 when none; 0 = exact height fields)")
      ->check(CLI::Range(0.0, kMaxOverhangAllowanceDeg));
  sub.add_option("--tolerance", args.tolerance,
                 "Deviation allowed, fraction of the bounding-box diagonal (default: the one decompose recorded "
                 "in decomposition.json, 0 when none = every block inside the input)")
      ->check(CLI::NonNegativeNumber);
  sub.add_flag("--against-input", args.against_input,
               "Check the blocks against MESH itself even where decompose repaired, smoothed or restored it "
               "(default: against what the blocks decompose, OUTDIR/input_*.obj): checks 4, 5 and 10 then allow "
               "the recorded tolerance plus the recorded deviations of that model from MESH (they add up), unless "
               "--tolerance is given; check 9 judges slivers at the recorded tolerance, as decompose did");
}

const RegisterCommand kRegisterValidate(make_command<ValidateArgs>(
    "validate", 30,
    "Check a decomposition written by `subfab decompose` against its input: (1) every block a closed, "
    "oriented 2-manifold with positive volume; (2) a height field along its direction (faces with "
    "n.d < -1e-3 only on the base); (3) no overlaps (exact, <= 1e-6 of the smaller block); (4) inside "
    "the input (exact, <= 1e-6 of the block outside); (5) the input surface covered (20000+ samples "
    "within 1e-5 x diagonal of a block); (6) height and machine limits; (7) machine meshes are the "
    "blocks moved rigidly; (8) machine meshes stay closed solids without self-intersections in single "
    "precision (float32, as STL stores them); (9) no slivers: no block thinner than max(1e-4 x diagonal, "
    "tolerance) where the model is thicker (thickness = mean chord length along the block's thinnest frame "
    "axis; each block's is printed); (10, within a tolerance) the deviation of the model made. When decompose repaired infeasible features (decomposition.json names "
    "OUTDIR/input_repaired.obj), checks 4 and 5 use the repaired input and say so, with the recorded "
    "deviation. Then, informational (never a failure): each block's milled shape (what a 3-axis machine "
    "makes of it: everything between its base and its top surface along its direction), with the filled "
    "volume, its deviation from the input, how much sticks out and milled-shape collisions. Exit 0 if all "
    "pass, 3 if one fails, 2 if the files cannot be read.",
    add_validate_options, run_validate));

}  // namespace
}  // namespace subfab::cli
