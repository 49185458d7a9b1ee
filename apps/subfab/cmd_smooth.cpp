// SPDX-License-Identifier: GPL-3.0-or-later
//! `subfab smooth MESH -o OUT [options]`: Taubin low-pass filter of a solid
//! before `subfab decompose` (thesis Section 4.3.5: fewer blocks for a small,
//! measured deviation), keeping it a valid solid (exact checks), and printing
//! the deviation. Exit 0 on success, 2 when the input is not a usable solid.
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "command.h"
#include "subfab/core/progress.h"
#include "subfab/fidelity/smooth_for_decomposition.h"
#include "subfab/mesh/read_mesh.h"
#include "subfab/mesh/write_mesh.h"

namespace subfab::cli {
namespace {

struct SmoothArgs {
  std::string mesh;
  std::string output;
  SmoothOptions options;
  std::string weights = "uniform";
  CommonOptions common;
};

std::string number(double x) {
  std::ostringstream out;
  out << std::setprecision(4) << x;
  return out.str();
}

int run_smooth(const SmoothArgs& args) {
  ConsoleProgress progress(std::cerr, args.common.quiet, stderr_is_terminal());
  SmoothOptions options = args.options;
  options.weights = args.weights == "cotangent" ? TaubinWeights::Cotangent : TaubinWeights::Uniform;
  options.progress = &progress;
  const SmoothResult result = transform_mesh_file(
      args.mesh, args.output, progress, args.common.quiet,
      [&options](const Mesh& mesh) { return smooth_for_decomposition(mesh, options); });  // InvalidMeshError: exit 2
  const SmoothReport& r = result.report;
  if (args.common.json) {
    nlohmann::ordered_json j;
    j["input"] = args.mesh;
    j["output"] = args.output;
    j["parameters"] = {{"passes", options.num_passes},
                       {"max_deviation", options.max_deviation},
                       {"lambda", options.lambda},
                       {"mu", options.mu},
                       {"weights", args.weights}};
    j["bbox_diagonal"] = r.bbox_diagonal;
    j["num_passes"] = r.num_passes;
    j["num_vertices"] = result.mesh.vertices.size();
    j["num_vertices_moved"] = r.num_vertices_moved;
    j["num_vertices_capped"] = r.num_vertices_capped;
    j["num_vertices_frozen"] = r.num_vertices_frozen;
    j["hausdorff"] = r.hausdorff;
    j["hausdorff_fraction"] = r.fraction(r.hausdorff);
    j["hausdorff_error"] = r.hausdorff_error;
    j["mean_deviation"] = r.mean_deviation;
    j["mean_deviation_fraction"] = r.fraction(r.mean_deviation);
    j["max_displacement"] = r.max_displacement;
    j["max_displacement_fraction"] = r.fraction(r.max_displacement);
    j["volume_change_fraction"] = r.input_volume > 0 ? r.volume / r.input_volume - 1 : 0.0;
    j["seconds"] = r.seconds;
    std::cout << j.dump(2) << "\n";
  } else if (!args.common.quiet) {
    std::ostringstream out;
    out << "smoothed " << args.mesh << " -> " << args.output << " (" << r.num_passes << " passes, "
        << r.num_vertices_moved << " of " << result.mesh.vertices.size() << " vertices moved, "
        << r.num_vertices_capped << " at the cap, " << r.num_vertices_frozen
        << " frozen to avoid self-intersections)\n";
    out << "deviation from the input (bbox diagonal " << number(r.bbox_diagonal) << "):\n";
    out << "  Hausdorff (symmetric)  " << number(r.hausdorff) << "  (" << number(r.fraction(r.hausdorff))
        << " of the diagonal, +- " << number(r.hausdorff_error) << ")\n";
    out << "  mean (area-weighted)   " << number(r.mean_deviation) << "  (" << number(r.fraction(r.mean_deviation))
        << " of the diagonal)\n";
    out << "  max vertex move        " << number(r.max_displacement) << "  ("
        << number(r.fraction(r.max_displacement)) << " of the diagonal)\n";
    out << "  volume change          "
        << number(r.input_volume > 0 ? 100 * (r.volume / r.input_volume - 1) : 0.0) << " %\n";
    out << "a closed, manifold, outward-oriented solid without self-intersections (checked exactly); decompose it "
           "with: subfab decompose "
        << args.output << " -o OUTDIR\n";
    std::cout << out.str();
  }
  return kExitOk;
}

void add_smooth_options(CLI::App& sub, SmoothArgs& args) {
  add_solid_input(sub, args.mesh);
  sub.add_option("-o,--output", args.output, "Output mesh file (.obj .off .ply .stl)")->required();
  sub.add_option("--passes", args.options.num_passes, "Taubin (lambda, mu) passes; more = smoother, up to the cap")
      ->default_val(args.options.num_passes)
      ->check(CLI::NonNegativeNumber);
  sub.add_option("--max-deviation", args.options.max_deviation,
                 "Cap on each vertex's displacement, fraction of the bbox diagonal (bounds the Hausdorff "
                 "distance to the input)")
      ->default_val(args.options.max_deviation)
      ->check(CLI::Range(0.0, 1.0));
  sub.add_option("--lambda", args.options.lambda, "Taubin shrink factor, in (0, 1)")
      ->default_val(args.options.lambda);
  sub.add_option("--mu", args.options.mu, "Taubin inflate factor, in (-1, -lambda)")->default_val(args.options.mu);
  sub.add_option("--weights", args.weights,
                 "Laplacian weights: uniform (Taubin's umbrella operator, stable on any mesh) or cotangent "
                 "(clamped, moves mostly along the normal)")
      ->default_val(args.weights)
      ->check(CLI::IsMember({"uniform", "cotangent"}));
}

const RegisterCommand kRegisterSmooth(make_command<SmoothArgs>(
    "smooth", 15,
    "Remove small surface details from a closed mesh with Taubin's lambda/mu low-pass filter (thesis "
    "Section 4.3.5), so that `subfab decompose` needs fewer blocks. Every vertex stays within "
    "--max-deviation x bbox diagonal of its input position; the result is checked exactly to be a "
    "closed, manifold, outward-oriented solid without self-intersections (a vertex whose move would "
    "break that is put back and frozen). Prints the deviation (Hausdorff, mean) and writes OUT. "
    "Exit 2 when the input is not a usable solid.",
    add_smooth_options, run_smooth));

}  // namespace
}  // namespace subfab::cli
