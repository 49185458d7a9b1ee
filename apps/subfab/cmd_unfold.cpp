// SPDX-License-Identifier: GPL-3.0-or-later
//! `subfab unfold MESH -o OUTDIR [options]`: unfoldable simplification for
//! V-groove milling (thesis Chapter 3): a polygonal model whose every fold a
//! V-bit can cut, its nets on sheets (SVG, DXF), a JSON description, a
//! preview picture and (unless --no-view) view.html.
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "command.h"
#include "subfab/core/error.h"
#include "subfab/unfold/export_unfolding.h"
#include "subfab/unfold/simplify_unfoldable.h"
#include "subfab/unfold/unfold_summary_to_json.h"
#include "subfab/view/write_unfolding_view.h"

namespace subfab::cli {
namespace {

struct UnfoldArgs {
  std::string mesh;
  std::string outdir;
  double granularity = 2.0;
  double min_facet_area = -1;
  std::string delete_facets;
  std::string sheet;
  bool no_masks = false;
  bool no_view = false;
  RepairInputOptions repair;
  CommonOptions common;
};

std::vector<int> parse_ids(const std::string& text) {
  std::vector<int> ids;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) {
    std::size_t used = 0;
    int id = -1;
    try {
      id = std::stoi(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != part.size() || id < 0)
      throw InvalidArgumentError("--delete-facets expects facet ids separated by commas (e.g. 3,17,42), got '" +
                                 text + "'");
    ids.push_back(id);
  }
  return ids;
}

std::pair<double, double> parse_sheet(const std::string& text) {
  const auto x = text.find_first_of("xX");
  const auto fail = [&] {
    return InvalidArgumentError("--sheet expects WxH, two positive numbers in model units (e.g. 600x400), got '" +
                                text + "'");
  };
  if (x == std::string::npos) throw fail();
  double v[2];
  const std::string parts[2] = {text.substr(0, x), text.substr(x + 1)};
  for (int k = 0; k < 2; ++k)
    if (!parse_positive_number(parts[k], v[k])) throw fail();
  return {v[0], v[1]};
}

int run_unfold(const UnfoldArgs& args) {
  SimplifyUnfoldableOptions options;
  options.granularity = args.granularity;
  options.min_facet_area = args.min_facet_area;
  options.masks = !args.no_masks;
  if (!args.delete_facets.empty()) options.delete_facet_ids = parse_ids(args.delete_facets);
  ExportUnfoldingOptions export_options;
  if (!args.sheet.empty()) std::tie(export_options.sheet_width, export_options.sheet_height) = parse_sheet(args.sheet);

  ConsoleProgress progress(std::cerr, args.common.quiet, stderr_is_terminal());
  options.progress = &progress;
  export_options.progress = &progress;
  // IoError / InvalidMeshError: exit 2 (with --repair, the repaired solid)
  const SolidInput solid = read_solid_input(args.mesh, args.repair, args.outdir, progress);
  const Mesh& mesh = solid.mesh;
  const nlohmann::ordered_json mesh_repair = mesh_repair_record(solid);
  export_options.input = {{"path", args.mesh},
                          {"mesh_repair", mesh_repair},
                          {"unfolded_mesh", mesh_repair.is_null() ? args.mesh : std::string(kMeshRepairedFile)}};
  const SimplifyUnfoldableResult result = simplify_unfoldable(mesh, options);
  export_unfolding(result.mesh, result.unfolding, result.summary, args.outdir, export_options);
  const std::filesystem::path view_page = std::filesystem::path(args.outdir) / "view.html";
  if (args.no_view) {
    remove_stale_page(view_page);
  } else {
    StageScope stage(&progress, "view");
    write_view_or_warn(progress, view_page, [&] {
      UnfoldingViewOptions view;
      view.input = &mesh;
      write_unfolding_view(args.outdir, view);
    });
  }
  if (!args.common.quiet) progress.print_timings(std::cerr);

  const UnfoldSummary& s = result.summary;
  if (args.common.json) {
    nlohmann::ordered_json j;
    j["input"] = args.mesh;
    j["output"] = args.outdir;
    j["mesh_repair"] = mesh_repair;
    j["spacing"] = result.spacing;
    j["min_facet_area"] = result.min_facet_area;
    j.update(unfold_summary_to_json(s));  // facets_mc ... hausdorff
    j["hausdorff_over_spacing"] = result.spacing > 0 ? s.hausdorff / result.spacing : 0.0;
    j["hausdorff_after_masks"] = result.hausdorff_after_masks;
    j["refold_error"] = result.refold_error;
    j["diagonal"] = bounding_box(mesh).diagonal();
    j["deletions_refused"] = result.failures.size();
    std::cout << j.dump(2) << "\n";
  } else if (!args.common.quiet) {
    std::cout << s.facets_final << " facets (" << s.facets_mc << " after marching cubes, " << s.facets_after_masks
              << " after masks) in " << s.nets << " net(s), Hausdorff distance " << s.hausdorff << " ("
              << (result.spacing > 0 ? s.hausdorff / result.spacing : 0.0) << " x grid spacing); written to "
              << args.outdir << "\n";
  }
  return kExitOk;
}

void add_unfold_options(CLI::App& sub, UnfoldArgs& args) {
  add_solid_input(sub, args.mesh);
  add_output_folder(sub, args.outdir);
  sub.add_option("--granularity", args.granularity,
                 "Grid spacing = average edge length x G (default 2; larger gives fewer, bigger facets)")
      ->check(CLI::PositiveNumber);
  sub.add_option("--min-facet-area", args.min_facet_area,
                 "Facets smaller than this (model units^2) are deleted automatically when the hole can be "
                 "closed (default: 4 x grid spacing^2; 0 disables)")
      ->check(CLI::NonNegativeNumber);
  sub.add_option("--delete-facets", args.delete_facets,
                 "Comma-separated facet ids to delete as well, as numbered in the output of the same command "
                 "without this option (nets.svg, unfold.json); adjacent ids are deleted together");
  sub.add_option("--sheet", args.sheet,
                 "Sheet size WxH in model units; nets are packed on as many sheets as needed (default: one "
                 "large sheet)");
  sub.add_flag("--no-view", args.no_view, "Do not write OUTDIR/view.html (the model and its nets in 3D in a browser)");
  sub.add_flag("--no-masks", args.no_masks,
               "Skip the mask stage (thesis 3.3.1, Appendix A): more facets, closer to the input");
  add_repair_input_options(sub, args.repair);
}

const RegisterCommand kRegisterUnfold(make_command<UnfoldArgs>(
    "unfold", 30,
    "Simplify a closed mesh into planar facets whose normals are among the 26 lattice directions, so every "
    "fold can be cut with a V-bit, and unfold it into nets (thesis Chapter 3). Writes OUTDIR/simplified.obj, "
    "nets.svg, nets.dxf, unfold.json, preview.png and view.html (3D view in a browser; --no-view to skip). Exit 2 if the mesh is not a closed, manifold, "
    "consistently oriented solid (--repair repairs it first, as `subfab repair`).",
    add_unfold_options, run_unfold));

}  // namespace
}  // namespace subfab::cli
