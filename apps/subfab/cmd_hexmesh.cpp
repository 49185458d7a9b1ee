// SPDX-License-Identifier: GPL-3.0-or-later
//! `subfab hexmesh MESH -o OUTDIR [options]`: skeleton-driven all-hexahedral
//! mesh of a tubular solid (thesis Appendix D). Writes hexmesh.mesh (Medit),
//! hexmesh.vtk (legacy VTK with the scaled Jacobian per cell), hexmesh.json,
//! skeleton.skel, preview.png and (unless --no-view) view.html. Exit 2 for an
//! unusable solid or skeleton file, 3 when the mesh is not valid (inverted element or non-conforming).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "command.h"
#include "subfab/core/error.h"
#include "subfab/core/progress.h"
#include "subfab/hex/hexmesh.h"
#include "subfab/hex/read_skeleton.h"
#include "subfab/hex/write_hex_mesh.h"
#include "subfab/hex/write_skeleton.h"
#include "subfab/view/write_hex_mesh_view.h"

namespace subfab::cli {
namespace {

struct HexmeshArgs {
  std::string mesh;
  std::string outdir;
  std::string skeleton;
  bool scaling = false;
  bool no_scaling = false;
  bool no_mean_pass = false;
  bool keep_layers = false;
  bool no_layer_trial = false;
  bool no_view = false;
  int subdivisions = -1;
  std::size_t max_hexes = HexMeshOptions{}.max_hexes;
  CommonOptions common;
};

nlohmann::ordered_json to_json(const HexmeshArgs& args, const Mesh& input, const HexMeshResult& r,
                               const std::vector<std::pair<std::string, double>>& timings) {
  nlohmann::ordered_json j;
  j["input"] = args.mesh;
  j["output"] = args.outdir;
  j["input_triangles"] = input.faces.size();
  j["skeleton"] = args.skeleton.empty() ? "computed" : args.skeleton;
  j["skeleton_nodes"] = r.skeleton.num_nodes();
  j["resampled_nodes"] = r.resampled.num_nodes();
  j["cubes"] = r.structure_info.num_cubes;
  j["subdivided_cubes"] = r.structure_info.num_subdivided_cubes;
  j["tubes"] = r.structure_info.num_tubes;
  j["structure_hexahedra"] = r.structure.num_hexes();
  j["subdivisions"] = r.subdivisions;
  j["min_subdivisions"] = r.min_subdivisions;
  j["keep_layers"] = {{"enabled", r.keep_layers}, {"sheets_kept", r.kept_layer_sheets}};
  {
    const LayerTrial& t = r.layer_trial;
    nlohmann::ordered_json lt{{"tried", t.tried}, {"kept", t.kept}};
    if (t.tried)
      lt["not_kept"] = {{"hexahedra", t.hexes},
                        {"avg_scaled_jacobian", t.avg_sj},
                        {"min_scaled_jacobian", t.min_sj},
                        {"mean_distance_fraction", r.diagonal > 0 ? t.mean_distance / r.diagonal : 0.0},
                        {"seconds", t.seconds}};
    j["layer_trial"] = lt;
  }
  {  // D.5: the cones found and used, the integer programme
    const ResolutionPlan& p = r.resolution;
    nlohmann::ordered_json rc;
    rc["enabled"] = r.resolution_control;
    rc["cones_found"] = r.cones_found.size();
    rc["cones_used"] = p.layers.size();
    nlohmann::ordered_json cones = nlohmann::ordered_json::array();
    for (const Cone& c : r.cones_found) {
      const bool used = std::any_of(p.layers.begin(), p.layers.end(), [&](const ConeLayer& l) { return l.hexes[0] == c.hex; });
      const int tip = used ? p.splits[static_cast<std::size_t>(c.hex)] : -1;
      cones.push_back({{"hexahedron", c.hex}, {"arc", c.arc}, {"area_ratio", c.ratio}, {"used", used},
                       {"tip_splits", used ? tip + r.min_subdivisions : -1},
                       {"base_splits", used ? tip + 1 + r.min_subdivisions : -1}});
    }
    rc["cones"] = cones;
    std::size_t pieces = 0;
    double worst = 1;
    for (std::size_t h = 0; h < r.in_cone_template.size() && h < r.scaled_jacobian.size(); ++h)
      if (r.in_cone_template[h] >= 0) ++pieces, worst = std::min(worst, r.scaled_jacobian[h]);
    rc["template_hexahedra"] = pieces;  // the pieces of the cone templates, after their splits
    if (pieces > 0) rc["template_min_scaled_jacobian"] = worst;
    rc["ilp"] = {{"variables", p.num_variables}, {"constraints", p.num_constraints}, {"solved", p.solved},
                 {"seconds", p.ilp_seconds}};
    j["resolution_control"] = rc;
  }
  j["vertices"] = r.mesh.num_vertices();
  j["hexahedra"] = r.mesh.num_hexes();
  j["boundary_quads"] = r.check.num_boundary_quads;
  j["conforming"] = r.check.valid();
  j["scaled_jacobian"] = {{"min", r.min_sj}, {"avg", r.avg_sj}, {"max", r.max_sj}};
  nlohmann::ordered_json hist;
  hist["<=0"] = r.histogram[0];
  for (int b = 1; b <= 10; ++b) {
    std::ostringstream key;
    key << std::fixed << std::setprecision(1) << (b - 1) / 10.0 << "-" << b / 10.0;
    hist[key.str()] = r.histogram[static_cast<std::size_t>(b)];
  }
  j["scaled_jacobian_histogram"] = hist;
  j["inverted"] = r.histogram[0];
  j["final_pass"] = {{"min_before", r.raise.min_before},
                     {"inverted_before", r.raise.num_inverted_before},
                     {"moves", r.raise.num_moves},
                     {"untangle_steps", r.raise.untangle_steps},
                     {"sweeps", r.raise.sweeps},
                     {"boundary_vertices_off_surface", r.raise.num_off_surface},
                     {"repaired_worst", r.raise.repaired_worst},
                     {"loose_boundary_vertices_moved", r.raise.num_loose_moved}};
  j["pull_boundary"] = {{"off_surface_before", r.pull.off_before},
                        {"off_surface_after", r.pull.off_after},
                        {"max_off_before_fraction", r.diagonal > 0 ? r.pull.max_off_before / r.diagonal : 0.0},
                        {"max_off_after_fraction", r.diagonal > 0 ? r.pull.max_off_after / r.diagonal : 0.0},
                        {"moves", r.pull.moves},
                        {"sweeps", r.pull.sweeps},
                        {"held", r.pull.held},
                        {"snapped", r.pull.snapped},
                        {"closer", r.pull.closer},
                        {"snap_steps", r.pull.snap_steps}};
  j["worst_pass"] = {{"min_before", r.worst.min_before},
                     {"avg_before", r.worst.avg_before},
                     {"targets_before", r.worst.targets_before},
                     {"targets_after", r.worst.targets_after},
                     {"min_after", r.worst.min_after},
                     {"avg_after", r.worst.avg_after},
                     {"patches", r.worst.patches},
                     {"steps", r.worst.steps},
                     {"rounds", r.worst.rounds}};
  j["mean_pass"] = {{"enabled", !args.no_mean_pass},
                    {"avg_before", r.mean.avg_before},
                    {"min_before", r.mean.min_before},
                    {"moves", r.mean.num_moves},
                    {"sweeps", r.mean.sweeps}};
  j["diagonal"] = r.diagonal;
  j["mean_distance_fraction"] = r.diagonal > 0 ? r.mean_distance / r.diagonal : 0.0;
  j["max_distance_fraction"] = r.diagonal > 0 ? r.max_distance / r.diagonal : 0.0;
  j["mean_vertex_distance_fraction"] = r.diagonal > 0 ? r.mean_vertex_distance / r.diagonal : 0.0;
  j["max_vertex_distance_fraction"] = r.diagonal > 0 ? r.max_vertex_distance / r.diagonal : 0.0;
  j["boundary_vertices"] = r.boundary_vertices;
  j["vertices_off_surface"] = r.vertices_off_surface;  // boundary vertices over 1e-6 of the diagonal from the input
  nlohmann::ordered_json t;
  double total = 0;
  for (const auto& [name, s] : timings) t[name] = s, total += s;
  j["seconds"] = t;
  j["seconds_total"] = total;
  return j;
}

//! The mesh, its qualities and the structure as the view module takes them.
HexMeshView hex_mesh_view(const HexmeshArgs& args, const Mesh& input, const HexMeshResult& r) {
  HexMeshView view;
  view.mesh = {r.mesh.vertices, r.mesh.hexes};
  view.scaled_jacobian = r.scaled_jacobian;
  view.structure = {r.structure.vertices, r.structure.hexes};
  view.input = &input;
  view.input_name = std::filesystem::path(args.mesh).filename().string();
  return view;
}

int run_hexmesh(const HexmeshArgs& args) {
  ConsoleProgress progress(std::cerr, args.common.quiet, stderr_is_terminal());
  const auto start = std::chrono::steady_clock::now();
  const Mesh mesh = read_closed_solid(args.mesh, progress);  // IoError / InvalidMeshError: exit 2
  Skeleton skeleton;
  if (!args.skeleton.empty()) {
    StageScope stage(&progress, "read skeleton");
    skeleton = read_skeleton(args.skeleton);  // IoError: exit 2, with the line
  }
  const double read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  HexMeshOptions options;
  options.progress = &progress;
  options.subdivisions = args.subdivisions;
  options.resolution_control = !args.no_scaling;
  options.max_hexes = args.max_hexes;
  options.raise_mean = !args.no_mean_pass;
  options.keep_layers = args.keep_layers;
  options.layer_trial = !args.no_layer_trial;
  HexMeshResult result;
  try {
    result = hexmesh(mesh, args.skeleton.empty() ? nullptr : &skeleton, options);
  } catch (const InvalidArgumentError& e) {  // a bad skeleton file is bad input
    throw IoError(args.skeleton + ": " + e.what());
  }
  const std::filesystem::path out(args.outdir);
  std::vector<std::pair<std::string, double>> timings{{"read", read_seconds}};
  timings.insert(timings.end(), result.timings.begin(), result.timings.end());
  {
    StageScope stage(&progress, "write");
    const auto t0 = std::chrono::steady_clock::now();
    std::error_code ec;
    std::filesystem::create_directories(out, ec);
    if (ec) throw IoError("cannot create the output folder " + out.string() + ": " + ec.message());
    write_medit_hex_mesh(result.mesh, out / "hexmesh.mesh");
    write_vtk_hex_mesh(result.mesh, out / "hexmesh.vtk", result.scaled_jacobian);
    write_skeleton(result.skeleton, out / "skeleton.skel");
    write_hex_mesh_preview(hex_mesh_view(args, mesh, result), out / "preview.png");
    timings.emplace_back("write", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    std::ofstream json(out / "hexmesh.json");
    json << to_json(args, mesh, result, timings).dump(2) << "\n";
    if (!json) throw IoError("cannot write " + (out / "hexmesh.json").string());
  }
  if (args.no_view) {
    remove_stale_page(out / "view.html");
  } else {
    StageScope stage(&progress, "view");
    write_view_or_warn(progress, out / "view.html",
                       [&] { write_hex_mesh_view(hex_mesh_view(args, mesh, result), out / "view.html"); });
  }
  if (!args.common.quiet) progress.print_timings(std::cerr);
  if (args.common.json) {
    std::cout << to_json(args, mesh, result, timings).dump(2) << "\n";
  } else if (!args.common.quiet) {
    std::cout << result.mesh.num_hexes() << " hexahedra (" << result.structure.num_hexes()
              << " in the tubular structure, " << result.subdivisions << " subdivisions), scaled Jacobian min "
              << result.min_sj << " avg " << result.avg_sj << ", " << result.histogram[0]
              << " inverted; boundary distance to the input: mean "
              << (result.diagonal > 0 ? result.mean_distance / result.diagonal : 0.0) << ", max "
              << (result.diagonal > 0 ? result.max_distance / result.diagonal : 0.0)
              << " of the diagonal (its vertices: mean "
              << (result.diagonal > 0 ? result.mean_vertex_distance / result.diagonal : 0.0) << ", max "
              << (result.diagonal > 0 ? result.max_vertex_distance / result.diagonal : 0.0) << "); written to " << args.outdir << "\n";
  }
  if (!result.check.valid()) {
    std::cerr << "error: the hexahedral mesh is not conforming (this is a bug; please report it with the input)\n";
    return kExitFailed;
  }
  if (result.histogram[0] > 0) {
    std::cerr << "error: " << result.histogram[0]
              << " hexahedra are inverted or degenerate (scaled Jacobian <= 0); the mesh was written but is "
                 "not usable for simulation. A cleaner skeleton (--skeleton) may help.\n";
    return kExitFailed;
  }
  return kExitOk;
}

void add_hexmesh_options(CLI::App& sub, HexmeshArgs& args) {
  add_solid_input(sub, args.mesh);
  add_output_folder(sub, args.outdir);
  sub.add_option("--skeleton", args.skeleton,
                 "Curve-skeleton in the .skel format (header line, node count, then 'id x y z radius n "
                 "neighbours...' per node); computed (mean curvature flow + automatic clean-up) when absent")
      ->check(CLI::ExistingFile);
  auto* scaling = sub.add_flag("--scaling", args.scaling,
                               "Resolution control (thesis D.5): cones on terminal branches, their templates and the "
                               "integer programme of the splits (CBC), so thick parts get more hexahedra across than "
                               "thin limbs (the default; the flag only says so)");
  sub.add_flag("--no-scaling", args.no_scaling,
               "No resolution control (D.5): every hexahedron is split the same number of times")
      ->excludes(scaling);
  sub.add_flag("--no-mean-pass", args.no_mean_pass,
               "Skip the last stage that raises the average scaled Jacobian (raise_mean_scaled_jacobian, the "
               "minimum kept); for comparison");
  sub.add_flag("--keep-layers", args.keep_layers,
               "The finest level splits across the tubes only (their layers along the skeleton are left whole, "
               "fewer hexahedra touching the structure's irregular edges); the automatic number of levels counts "
               "it. With --no-scaling: cactus 3488 hexahedra, SJ .926 / .620 (docs/hexmesh.md)");
  sub.add_flag("--no-layer-trial", args.no_layer_trial,
               "Do not try the layer-keeping mesh (--keep-layers --no-scaling) next to the default one on small "
               "models (at most 5000 hexahedra, automatic subdivisions; the second mesh is kept when no worse in "
               "average and minimum scaled Jacobian and mean distance)");
  sub.add_flag("--no-view", args.no_view,
               "Do not write OUTDIR/view.html (the cells coloured by scaled Jacobian in 3D in a browser)");
  sub.add_option("--subdivisions", args.subdivisions,
                 "Regular 2x2x2 splits after pillowing of the least split hexahedra (all of them without cones; "
                 "default: automatic, the most that stays under --max-hexes)")
      ->check(CLI::Range(0, 6));
  sub.add_option("--max-hexes", args.max_hexes, "Bound on the hexahedra for the automatic number of subdivisions")
      ->default_val(args.max_hexes)
      ->check(CLI::PositiveNumber);
}

const RegisterCommand kRegisterHexmesh(make_command<HexmeshArgs>(
    "hexmesh", 40,
    "Skeleton-driven all-hexahedral mesh of a tubular closed solid (thesis Appendix D): computes or reads a "
    "curve-skeleton, resamples it, builds a conforming structure of cubes and tubes, pads, subdivides, "
    "projects onto the surface and optimises the scaled Jacobian. Writes hexmesh.mesh (Medit), hexmesh.vtk "
    "(VTK, scaled Jacobian per cell), hexmesh.json, skeleton.skel, preview.png (boundary coloured by quality "
    "beside the tubular structure) and view.html (3D view in a browser; --no-view to skip). Exit 2 if the input is not a closed "
    "solid or the skeleton file is malformed, 3 if the mesh has an inverted element.",
    add_hexmesh_options, run_hexmesh));

}  // namespace
}  // namespace subfab::cli
