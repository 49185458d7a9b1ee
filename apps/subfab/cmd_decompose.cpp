// SPDX-License-Identifier: GPL-3.0-or-later
//! `subfab decompose MESH -o OUTDIR [options]`: height-field block
//! decomposition (thesis Chapter 4), written as OUTDIR/decomposition.json,
//! OUTDIR/blocks/block_NNN.obj (input frame), OUTDIR/mill/block_NNN.stl
//! (ready to mill: direction +Z, base on z = 0), and unless --no-view
//! OUTDIR/view.html and OUTDIR/assembly.html (src/view).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "command.h"
#include "subfab/core/error.h"
#include "subfab/decompose/decompose.h"
#include "subfab/decompose/decompose_smoothed.h"
#include "subfab/decompose/export_decomposition.h"
#include "subfab/mesh/write_mesh.h"
#include "subfab/validate/block_name.h"
#include "subfab/view/write_assembly_sheet.h"
#include "subfab/view/write_decomposition_view.h"

namespace subfab::cli {
namespace {

struct DecomposeArgs {
  std::string mesh;
  std::string outdir;
  double max_height = std::numeric_limits<double>::infinity();
  double max_height_abs = std::numeric_limits<double>::infinity();
  std::string machine;
  bool no_orient = false;
  double grid_factor = 1.0;
  bool exact = false;
  double max_deviation = 0.005;
  double max_overhang = 0.0;
  double tolerance = 0.0;
  double tolerance_abs = std::numeric_limits<double>::infinity();
  double tolerance_floors = DecomposeOptions{}.tolerance_floor_scale;
  double tolerance_locate = DecomposeOptions{}.tolerance_locate_margin;
  int tolerance_rounds = DecomposeOptions{}.tolerance_rounds;
  bool tolerance_given = false;  // --tolerance or --tolerance-abs on the command line (even 0)
  bool tolerance_fraction_given = false;  // --tolerance on the command line
  std::optional<double> smooth;  // --smooth [F]: smoothing cap, fraction of the diagonal
  SmoothOptions smoothing;        // with --smooth: --smooth-passes, --smooth-lambda, --smooth-mu
  bool no_view = false;
  RepairInputOptions repair;
  CommonOptions common;
};

//! The tolerance (x bbox diagonal) decompose falls back to, without
//! --tolerance, where the thin-feature repair gives up: a hobby machine
//! holds about 0.1 mm on a 200 mm part (issue 17).
constexpr double kFallbackTolerance = 5e-4;

Vec3 parse_machine(const std::string& text) {
  const auto fail = [&text]() {
    return InvalidArgumentError("--machine expects X,Y,Z: three positive numbers in model units, got '" + text + "'");
  };
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) parts.push_back(part);
  if (parts.size() != 3) throw fail();
  Vec3 v;
  for (int k = 0; k < 3; ++k)
    if (!parse_positive_number(parts[static_cast<std::size_t>(k)], v[k])) throw fail();
  return v;
}

//! The "input"."smoothing" record of decomposition.json (and of --json).
nlohmann::ordered_json smoothing_record(const SmoothedDecomposeReport& r, const SmoothOptions& o) {
  // What the blocks decompose, and its deviation from the input: the restored
  // solid (measured), or within a tolerance the smoothed model (its vertices'
  // largest move bounds its Hausdorff distance; measured within
  // hausdorff_error: smoothed_max_deviation_fraction).
  const bool restored = !r.within_tolerance;
  const double max = restored ? r.max_deviation : r.decomposed_deviation;
  const double mean = restored ? r.mean_deviation : r.smoothed_mean_deviation;
  nlohmann::ordered_json j = {{"mesh", restored ? kRestoredInputFile : kSmoothedInputFile},
                              {"smoothed_mesh", kSmoothedInputFile},
                              {"restored", restored},
                              {"cap_fraction", o.max_deviation},
                              {"passes", r.smooth.num_passes},
                              {"lambda", o.lambda},
                              {"mu", o.mu}};
  if (restored) j["num_blocks_smoothed"] = r.num_blocks_smoothed;
  j["num_blocks"] = r.num_blocks;
  j["max_deviation"] = max;
  j["mean_deviation"] = mean;
  j["max_deviation_fraction"] = r.fraction(max);
  j["mean_deviation_fraction"] = r.fraction(mean);
  j["hausdorff_error"] = restored ? r.deviation_error : r.smooth.hausdorff_error;
  j["smoothed_max_deviation_fraction"] = r.fraction(r.smooth.hausdorff);
  j["smoothed_mean_deviation_fraction"] = r.fraction(r.smoothed_mean_deviation);
  if (restored) {
    j["num_vertices_restored"] = r.restore.num_restored;
    j["num_vertices_at_smoothed"] = r.restore.num_at_smoothed;
    j["num_vertices_held_on_box"] = r.restore.num_held_on_box;
    j["num_vertices_held_back"] = r.restore.num_held_back;
    j["num_restore_rounds"] = r.restore.num_rounds;
    j["num_carve_rounds"] = r.num_carve_rounds;
  } else {
    j["tolerance"] = r.tolerance;
    j["tolerance_fraction"] = r.fraction(r.tolerance);
    // the blocks from the input: smoothing + the tolerance's measured bound (triangle inequality)
    j["total_deviation_bound"] = r.max_deviation;
    j["total_deviation_bound_fraction"] = r.fraction(r.max_deviation);
  }
  j["smooth_seconds"] = r.smooth.seconds;
  if (restored) j["restore_seconds"] = r.restore_seconds;
  return j;
}

int run_decompose(const DecomposeArgs& args) {
  DecomposeOptions options;
  options.max_height_fraction = args.max_height;
  options.max_height_abs = args.max_height_abs;
  if (!args.machine.empty()) options.machine = parse_machine(args.machine);
  options.orient = !args.no_orient;
  options.grid_factor = args.grid_factor;
  options.repair = !args.exact;
  options.max_deviation = args.max_deviation;
  options.max_overhang_deg = args.max_overhang;
  options.tolerance_fraction = args.tolerance;
  options.tolerance_abs = args.tolerance_abs;
  // --tolerance-abs alone: the fraction must not bound it (the smaller wins,
  // and 0 would mean exact blocks); a whole diagonal bounds nothing.
  if (!args.tolerance_fraction_given && std::isfinite(args.tolerance_abs)) options.tolerance_fraction = 1.0;
  options.tolerance_floor_scale = args.tolerance_floors;
  options.tolerance_locate_margin = args.tolerance_locate;
  options.tolerance_carry_boxes = args.tolerance_locate >= 0;  // negative: the rounds as before session 35
  options.tolerance_rounds = args.tolerance_rounds;
  // Where the thin-feature repair gives up, decompose within 5e-4 x diagonal
  // rather than fail, unless the user chose exactness or another trade.
  if (!args.tolerance_given && !args.exact && !(args.max_overhang > 0) && !args.smooth)
    options.fallback_tolerance_fraction = kFallbackTolerance;

  ConsoleProgress progress(std::cerr, args.common.quiet, stderr_is_terminal());
  options.progress = &progress;
  // IoError / InvalidMeshError: exit 2 (with --repair, the repaired solid)
  const SolidInput solid = read_solid_input(args.mesh, args.repair, args.outdir, progress);
  const Mesh& mesh = solid.mesh;
  const nlohmann::ordered_json mesh_repair = mesh_repair_record(solid);
  std::optional<SmoothedDecomposeResult> smoothed;
  nlohmann::ordered_json smoothing = nullptr;
  if (args.smooth) {  // thesis 4.3.5: smooth, decompose, restore the details, carve again
    SmoothedDecomposeOptions so;
    so.decompose = options;
    so.smooth = args.smoothing;
    so.smooth.max_deviation = *args.smooth;
    smoothed = decompose_smoothed(mesh, so);
    smoothing = smoothing_record(smoothed->report, so.smooth);
  }
  const DecomposeResult result = smoothed ? std::move(smoothed->decomposition) : decompose(mesh, options);
  std::vector<ExportedBlock> blocks;
  {
    StageScope stage(&progress, "export");
    ExportInfo info;
    info.input_path = args.mesh;
    info.options = options;
    info.mesh_repair = mesh_repair;
    info.smoothing = smoothing;
    blocks = export_decomposition(mesh, result, info, args.outdir);
    // The repaired or restored input (what the blocks decompose) next to the
    // blocks; stale ones from an earlier run are removed.
    const std::filesystem::path dir(args.outdir);
    std::error_code ec;
    for (const char* name : {kRepairedInputFile, kRestoredInputFile, kSmoothedInputFile})
      std::filesystem::remove(dir / name, ec);
    if (smoothed && smoothed->report.within_tolerance) {
      write_mesh(*result.repaired_input, dir / kSmoothedInputFile);  // what the blocks decompose
    } else if (smoothed) {
      write_mesh(*result.repaired_input, dir / kRestoredInputFile);
      write_mesh(smoothed->smoothed, dir / kSmoothedInputFile);
    } else if (result.repaired_input) {
      write_mesh(*result.repaired_input, dir / kRepairedInputFile);
    }
  }
  const std::filesystem::path view_page = std::filesystem::path(args.outdir) / "view.html";
  const std::filesystem::path sheet_page = std::filesystem::path(args.outdir) / "assembly.html";
  if (args.no_view) {
    remove_stale_page(view_page);
    remove_stale_page(sheet_page);
  } else {
    StageScope stage(&progress, "view");
    write_view_or_warn(progress, view_page, [&] {
      write_decomposition_view(args.outdir, {.model = result.repaired_input ? &*result.repaired_input : &mesh, .html = {},
                                             .progress = &progress});
    });
    write_view_or_warn(progress, sheet_page, [&] {
      AssemblySheetOptions sheet;
      sheet.progress = &progress;
      write_assembly_sheet(args.outdir, sheet);
    });
  }
  if (smoothed && smoothed->report.within_tolerance && !args.common.quiet) {
    const SmoothedDecomposeReport& r = smoothed->report;
    std::ostringstream msg;
    msg << "SMOOTHED, THEN WITHIN A TOLERANCE (--smooth " << *args.smooth << ", tolerance "
        << r.fraction(r.tolerance) << " x diagonal): " << r.num_blocks << " blocks decompose " << args.outdir << "/"
        << kSmoothedInputFile << " (vertices moved at most " << r.fraction(r.decomposed_deviation)
        << " x diagonal, mean " << r.fraction(r.smoothed_mean_deviation) << ") within the tolerance, not "
        << args.mesh << ": the deviations add up, the blocks lie within " << r.max_deviation << " ("
        << r.fraction(r.max_deviation) << " x diagonal) of the input; subfab validate checks the blocks against " << kSmoothedInputFile << " within the tolerance";
    progress.warn(msg.str());
  } else if (smoothed && !args.common.quiet) {
    const SmoothedDecomposeReport& r = smoothed->report;
    std::ostringstream msg;
    msg << "SMOOTHED AND RESTORED (--smooth " << *args.smooth << "): the smoothed model (Hausdorff "
        << r.fraction(r.smooth.hausdorff) << ", mean " << r.fraction(r.smoothed_mean_deviation)
        << " x diagonal from the input) gave " << r.num_blocks_smoothed << " blocks; with its details restored, "
        << r.num_blocks << " blocks decompose " << args.outdir << "/" << kRestoredInputFile
        << ", not the input: deviation of the blocks from the input " << args.mesh << ": Hausdorff "
        << r.max_deviation << " (" << r.fraction(r.max_deviation) << " x diagonal), mean " << r.mean_deviation
        << " (" << r.fraction(r.mean_deviation) << " x diagonal); subfab validate checks the blocks against "
        << kRestoredInputFile;
    progress.warn(msg.str());
  }
  if (result.repaired_input && !smoothed && !args.common.quiet) {
    const RepairReport& r = result.repair;
    std::ostringstream msg;
    if (result.num_snapped_vertices > 0 && r.num_features == 0)
      msg << "SNAPPED INPUT: the chosen frame is feasible once the input's coordinates are snapped within the "
             "file's own rounding (+-"
          << result.coordinate_rounding << " per coordinate as stored): " << result.num_snapped_vertices
          << " vertices moved by at most " << r.max_deviation << " (" << r.max_deviation_fraction()
          << " of the diagonal), mean " << r.mean_deviation << "; the blocks decompose " << args.outdir << "/"
          << kRepairedInputFile << ", not the input (--no-orient keeps the input's frame and coordinates)";
    else
    msg << "REPAIRED INPUT: " << r.num_features << " infeasible feature(s) (" << r.num_creases << " creases, "
        << r.num_vertices << " vertices) smoothed locally; the blocks decompose " << args.outdir << "/"
        << kRepairedInputFile << ", not the input: Hausdorff deviation " << r.max_deviation << " ("
        << r.max_deviation_fraction() << " of the diagonal, cap " << args.max_deviation << "), mean "
        << r.mean_deviation << " (" << r.mean_deviation_fraction() << "); " << r.num_faces_removed
        << " input faces replaced by " << r.num_faces_new << " (use --exact to refuse instead)";
    progress.warn(msg.str());
  }
  double total = 0, smallest = std::numeric_limits<double>::infinity(), steepest = 0;
  std::size_t num_overhanging = 0;
  for (const auto& b : blocks) {
    total += b.volume;
    smallest = std::min(smallest, b.volume);
    steepest = std::max(steepest, b.max_overhang_deg);
    if (b.max_overhang_deg > 0.1) ++num_overhanging;
  }
  if (args.max_overhang > 0 && !args.common.quiet) {
    std::ostringstream msg;
    msg << "OVERHANGS ALLOWED (--max-overhang " << args.max_overhang << "): " << num_overhanging << " of "
        << blocks.size() << " blocks have faces leaning more than 0.1 deg past vertical, the steepest "
        << steepest << " deg; a 3-axis machine cannot cut them and leaves material under them. These are "
           "not exact height fields (subfab validate checks them against the same allowance, read from "
           "decomposition.json; --max-overhang 0 there checks exactness)";
    progress.warn(msg.str());
  }
  if (result.tolerance > 0 && !args.common.quiet) {
    const double diagonal = bounding_box(mesh).diagonal();
    std::ostringstream msg;
    msg << "WITHIN A TOLERANCE of " << result.tolerance << " (" << result.tolerance / diagonal
        << " x diagonal): " << result.num_tolerance_merges << " merges into milled shapes; ";
    if (result.num_blocks_decomposed_in_place > 0)
      msg << result.num_blocks_decomposed_in_place << " block(s) still beyond it after " << result.num_tolerance_rounds
          << " round(s) decomposed again on their own carved pieces; ";
    msg
        << std::count(result.filled.begin(), result.filled.end(), char{1})
        << " block(s) stick out of the input (undercuts filled), measured deviation bound "
        << result.deviation_bound << " (" << result.deviation_bound / diagonal
        << " x diagonal); every block is an exact height field (subfab validate checks the deviation)";
    if (result.tolerance_overhang_deg > 0)
      msg << "; the blocks of the overhang ladder at " << result.tolerance_overhang_deg
          << " deg (every face leaning at most that far past vertical allowed, then milled and measured)";
    msg << "; slivers (thinner than " << result.sliver_thickness / diagonal
        << " x diagonal where the model is thicker): " << result.num_slivers_merged << " merged, "
        << result.num_slivers_dropped << " dropped, " << result.num_slivers_thickened << " thickened, "
        << result.num_slivers_recarved
        << " decomposed again with a neighbour, " << result.num_slivers << " left";
    if (!result.tolerance_fallback.empty()) {
      const bool slivers = result.tolerance_fallback.find("(slivers)") != std::string::npos;
      msg << "; NOT EXACT: " << (slivers ? result.tolerance_fallback : std::string("the thin-feature repair gave up"))
          << ", so this tolerance (the default's fallback, at most " << kFallbackTolerance
          << " x diagonal) was used; --tolerance 0 " << (slivers ? "keeps the exact blocks instead" : "refuses instead");
    }
    if (result.num_features_within_tolerance > 0)
      msg << "; " << result.num_features_within_tolerance
          << " crease(s)/spike(s) no exact block can cover were left to the tolerance instead of the thin-feature "
             "repair";
    progress.warn(msg.str());
  }
  if (!args.common.quiet) progress.print_timings(std::cerr);

  const double input_volume = signed_volume(mesh);
  if (args.common.json) {
    const DecomposeTimings& t = result.timings;
    nlohmann::ordered_json j;
    j["input"] = args.mesh;
    j["output"] = args.outdir;
    j["num_blocks"] = blocks.size();
    j["num_grown_boxes"] = result.num_grown_boxes;
    j["num_selected_boxes"] = result.num_selected_boxes;
    j["num_ordered_boxes"] = result.num_ordered_boxes;
    j["num_cycle_splits"] = result.num_cycle_splits;
    j["num_merges"] = result.num_merges;
    j["num_refined_faces"] = result.num_refined_faces;
    if (result.repaired_input && !smoothed)
      j["repair"] = {{"mesh", (std::filesystem::path(args.outdir) / kRepairedInputFile).string()},
                     {"num_features", result.repair.num_features},
                     {"max_deviation", result.repair.max_deviation},
                     {"max_deviation_fraction", result.repair.max_deviation_fraction()},
                     {"mean_deviation", result.repair.mean_deviation}};
    else
      j["repair"] = nullptr;
    j["mesh_repair"] = mesh_repair;
    j["smoothing"] = smoothing;
    j["cover_optimal"] = result.cover_optimal;
    j["material_volume_fraction"] = input_volume > 0 ? total / input_volume : 0.0;
    j["min_block_volume_fraction"] = blocks.empty() || input_volume <= 0 ? 0.0 : smallest / input_volume;
    j["max_overhang_allowed_deg"] = args.max_overhang;
    j["max_overhang_deg"] = steepest;
    j["tolerance"] = result.tolerance;
    j["num_tolerance_merges"] = result.num_tolerance_merges;
    j["num_blocks_decomposed_in_place"] = result.num_blocks_decomposed_in_place;
    j["num_sticking_out"] = std::count(result.filled.begin(), result.filled.end(), char{1});
    j["deviation_bound"] = result.deviation_bound;
    j["num_features_within_tolerance"] = result.num_features_within_tolerance;
    j["tolerance_fallback"] =
        result.tolerance_fallback.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(result.tolerance_fallback);
    j["sliver_thickness"] = result.sliver_thickness;
    j["num_slivers"] = result.num_slivers;
    j["num_slivers_merged"] = result.num_slivers_merged;
    j["num_slivers_dropped"] = result.num_slivers_dropped;
    j["num_slivers_thickened"] = result.num_slivers_thickened;
    j["num_slivers_recarved"] = result.num_slivers_recarved;
    j["timings_s"] = {{"orient", t.orient}, {"repair", t.repair},   {"field", t.field}, {"grow", t.grow},
                      {"cover", t.cover},   {"resolve", t.resolve}, {"carve", t.carve}, {"tolerance", t.tolerance}, {"total", t.total}};
    std::cout << j.dump(2) << "\n";
  } else if (!args.common.quiet) {
    std::cout << blocks.size() << " blocks written to " << args.outdir << " (" << result.num_selected_boxes
              << " boxes chosen from " << result.num_grown_boxes << ", " << result.num_cycle_splits
              << " cycle splits, " << result.num_merges << " merges); check them with: subfab validate "
              << args.mesh << " " << args.outdir << "\n";
  }
  // Every block is valid in doubles (export checks it); a block whose STL the
  // float32 cleanup could not make a solid fails validate's check 8: say so
  // and exit 3 rather than 0 (the files are written).
  std::string bad_stl;
  std::size_t num_bad_stl = 0;
  for (std::size_t i = 0; i < blocks.size(); ++i)
    if (!blocks[i].single_precision_ok && num_bad_stl++ < 8) bad_stl += (bad_stl.empty() ? "" : ", ") + block_name(i);
  if (num_bad_stl > 0) {
    std::cerr << "error: " << num_bad_stl << " block(s) (" << bad_stl << (num_bad_stl > 8 ? ", ..." : "")
              << ") are not closed solids once rounded to float32 in their STL files (mill/): features thinner "
                 "than float32's resolution. Their OBJ files (blocks/, double precision) are valid; another grid "
                 "(--grid-factor 0.8 or 1.25) gives other blocks and may avoid it (subfab validate: check 8)\n";
    return kExitFailed;
  }
  return kExitOk;
}

void add_decompose_options(CLI::App& sub, DecomposeArgs& args) {
  add_solid_input(sub, args.mesh);
  add_output_folder(sub, args.outdir);
  sub.add_option("--max-height", args.max_height,
                 "Maximum block height along its milling direction, as a fraction of the bounding-box "
                 "diagonal (the 'Height' column of thesis Table 4.1; default: no limit)")
      ->check(CLI::PositiveNumber);
  sub.add_option("--max-height-abs", args.max_height_abs,
                 "Maximum block height in model units (default: no limit; with --max-height the smaller wins)")
      ->check(CLI::PositiveNumber);
  sub.add_option("--machine", args.machine,
                 "Machine work volume X,Y,Z in model units: every block must fit, Z along its milling "
                 "direction (default: no limit)");
  sub.add_flag("--no-orient", args.no_orient, "Keep the input frame (skip the orientation search of thesis 4.3.1)");
  sub.add_flag("--exact", args.exact,
               "Refuse (exit 3, listing them) when the chosen frame has creases or spikes that no axis-aligned "
               "height-field block can cover, instead of smoothing them locally (default: repair them, thesis "
               "4.3.5, and decompose OUTDIR/input_repaired.obj; the deviation is reported)");
  sub.add_option("--max-deviation", args.max_deviation,
                 "Cap on the local repair's Hausdorff distance from the input, as a fraction of the "
                 "bounding-box diagonal (default 0.005); exit 3 if the repair needs more")
      ->check(CLI::PositiveNumber);
  sub.add_option("--max-overhang", args.max_overhang,
                 "Let block faces lean up to DEG degrees past vertical (default 0: exact height fields). "
                 "A 3-axis machine cannot cut such faces and leaves material under them (at most their "
                 "height x tan(DEG) deep), so use it only when that is acceptable, e.g. for the noise of a "
                 "scanned model; it gives far fewer blocks. The thesis's published blocks lean up to 43 deg.")
      ->check(CLI::Range(0.0, kMaxOverhangAllowanceDeg));
  sub.add_option("--tolerance", args.tolerance,
                 "Deviation allowed, as a fraction of the bounding-box diagonal (default 0: exact blocks). "
                 "Touching blocks are merged into the shape a 3-axis machine mills of their union (undercuts "
                 "filled) while the symmetric Hausdorff distance between the model made and the input stays "
                 "within it; every block stays an exact height field and blocks do not overlap. Creases and spikes "
                 "no exact block can cover are left to the tolerance where their undercuts are within it (no "
                 "thin-feature repair there). Not given: exact blocks, except where the thin-feature repair gives "
                 "up: then 5e-4 (said and recorded); --tolerance 0 refuses instead (exit 3)")
      ->check(CLI::NonNegativeNumber)
      ->each([&args](const std::string&) { args.tolerance_given = args.tolerance_fraction_given = true; });
  sub.add_option("--tolerance-abs", args.tolerance_abs,
                 "Deviation allowed in model units (with --tolerance the smaller wins)")
      ->check(CLI::NonNegativeNumber)
      ->each([&args](const std::string&) { args.tolerance_given = true; });
  sub.add_option("--tolerance-floors", args.tolerance_floors,
                 "Within a tolerance T: also let a face whose undercut is deeper than q x T lean past vertical in "
                 "the blocks whose base lies at most S x q x T / |n.d| under it (the fill there is that short; "
                 "S = this, default 0.25; 0 = per face only; where a block fails the measure, the faces allowed in it step "
                 "down a level and their floors shrink with it, for up to 4 rounds (--tolerance-rounds); see "
                 "docs/decompose.md)")
      ->check(CLI::NonNegativeNumber);
  sub.add_option("--tolerance-locate", args.tolerance_locate,
                 "Within a tolerance T: where a block fails by points of the model made farther than T, only the "
                 "faces over those points (their boxes widened across the block's axis by this x T) get smaller "
                 "allowances in the next round, which starts from the boxes of the blocks that passed [1]; a "
                 "negative value: the rounds as before 2026-12-07 (every face in a failing block's box lowered, each "
                 "round grown afresh)")
      ->check(CLI::Number);
  sub.add_option("--tolerance-rounds", args.tolerance_rounds,
                 "Within a tolerance: decompositions under allowances, each milled and measured, before the blocks "
                 "still beyond the tolerance are decomposed again on their own carved pieces (within it, then "
                 "exactly) [4]")
      ->check(CLI::Range(1, 100));
  CLI::Option* smooth_option = sub.add_option("--smooth", args.smooth,
                 "Fewer blocks for a detailed model (thesis 4.3.5): smooth it (Taubin low-pass, as `subfab smooth`, "
                 "each vertex moved at most F x the bounding-box diagonal; F defaults to 0.005 when omitted: write "
                 "--smooth=F or put it after MESH), decompose the smoothed model, put the details back within its "
                 "blocks' regions and milling directions, and carve the blocks again. The blocks then decompose "
                 "OUTDIR/input_restored.obj (written, with OUTDIR/input_smoothed.obj), which subfab validate checks "
                 "them against; the deviation from the input is measured and reported. With --tolerance T: the "
                 "smoothed model is decomposed within T instead (no restoration; the blocks decompose "
                 "OUTDIR/input_smoothed.obj within T, and lie within F + T of the input, the bound reported). "
                 "Not with --max-overhang")
      ->expected(0, 1)
      ->default_str("0.005")
      ->check(CLI::NonNegativeNumber);
  sub.add_option("--smooth-passes", args.smoothing.num_passes,
                 "With --smooth: Taubin passes (as `subfab smooth --passes`). The cap F binds only when the passes "
                 "move vertices that far: 100 passes move max_planck's at most ~0.006 x diagonal; the thesis's own "
                 "smoothed statues moved theirs up to 0.017 (about 8000 passes here)")
      ->check(CLI::Range(1, 100000))
      ->needs(smooth_option);
  sub.add_option("--smooth-lambda", args.smoothing.lambda,
                 "With --smooth: Taubin shrink factor, in (0, 1) (as `subfab smooth --lambda`; 0.89 with "
                 "--smooth-mu -0.9, the defaults of the authors' own tool, give fewer blocks at the same deviation "
                 "on max_planck: bench/RESULTS.md)")
      ->default_val(args.smoothing.lambda)
      ->needs(smooth_option);
  sub.add_option("--smooth-mu", args.smoothing.mu, "With --smooth: Taubin inflate factor, in (-1, -lambda)")
      ->default_val(args.smoothing.mu)
      ->needs(smooth_option);
  sub.add_flag("--no-view", args.no_view, "Do not write OUTDIR/view.html (the 3D view in the browser) and OUTDIR/assembly.html (cut list and "
               "gluing order; `subfab assemble` writes it later, also in mm)");
  sub.add_option("--grid-factor", args.grid_factor,
                 "Grid spacing = average edge length x G (default 1; smaller is finer and slower)")
      ->check(CLI::PositiveNumber);
  add_repair_input_options(sub, args.repair);
}

const RegisterCommand kRegisterDecompose(make_command<DecomposeArgs>(
    "decompose", 20,
    "Split a closed mesh into non-overlapping height-field blocks, each millable in one pass of a "
    "3-axis machine (thesis Chapter 4). Writes OUTDIR/decomposition.json, OUTDIR/blocks/block_NNN.obj "
    "(input coordinates), OUTDIR/mill/block_NNN.stl (milling direction +Z, base on z = 0) and "
    "OUTDIR/view.html (the blocks in 3D in a browser) and OUTDIR/assembly.html (cut list, gluing order; "
    "--no-view skips both). "
    "Creases and spikes that no axis-aligned block can cover in the chosen frame are smoothed locally "
    "first (deviation capped by --max-deviation and reported; OUTDIR/input_repaired.obj is then what the "
    "blocks decompose), or refused with --exact. Exit 2 if the mesh is not a closed, manifold, consistently "
    "oriented solid (--repair repairs it first, as `subfab repair`); exit 3 if no valid decomposition was found, or (files written) when a block's STL is not a solid in float32.",
    add_decompose_options, run_decompose));

}  // namespace
}  // namespace subfab::cli
