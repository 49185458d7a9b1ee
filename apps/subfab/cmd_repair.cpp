// SPDX-License-Identifier: GPL-3.0-or-later
//! `subfab repair MESH -o OUT [--max-deviation F] [--json]`: turns a triangle
//! soup into a closed, manifold, outward-oriented solid without
//! self-intersections (repair_mesh), says what it changed and how far the
//! result is from the input. Exit 0 when OUT was written, 2 when the mesh
//! cannot be repaired within the cap (nothing is written).
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "command.h"
#include "subfab/mesh/read_mesh.h"
#include "subfab/mesh/write_mesh.h"
#include "subfab/repair/mesh_repair_to_json.h"
#include "subfab/repair/repair_mesh.h"

namespace subfab::cli {
namespace {

struct RepairArgs {
  std::string mesh;
  std::string output;
  MeshRepairOptions options;
  CommonOptions common;
};

int run_repair(const RepairArgs& args) {
  ConsoleProgress progress(std::cerr, args.common.quiet, stderr_is_terminal());
  MeshRepairOptions options = args.options;
  options.progress = &progress;
  const MeshRepairResult result = transform_mesh_file(
      args.mesh, args.output, progress, args.common.quiet,
      [&options](const Mesh& mesh) { return repair_mesh(mesh, options); });  // InvalidMeshError: exit 2
  const MeshRepairReport& r = result.report;
  if (args.common.json) {
    nlohmann::ordered_json j;
    j["input"] = args.mesh;
    j["output"] = args.output;
    j["changed"] = r.changed();
    j.update(mesh_repair_to_json(r));
    j["seconds"] = r.seconds;
    std::cout << j.dump(2) << "\n";
  } else if (!args.common.quiet) {
    std::ostringstream out;
    out << std::setprecision(4);
    if (!r.changed()) {
      out << args.mesh << " is already a valid solid (every check of subfab info passes); copied to " << args.output
          << "\n";
    } else {
      out << "problems found in " << args.mesh << ":\n";
      for (const auto& p : r.problems) out << "  " << p << "\n";
      out << "steps applied:\n";
      for (const auto& s : r.steps)
        if (s.applied()) out << "  " << std::left << std::setw(22) << s.name << s.message << "\n";
      out << "result: " << r.output_faces << " faces (input " << r.input_faces
          << "), a closed, manifold, outward-oriented solid without self-intersections (checked exactly)\n";
      out << "deviation from the input: Hausdorff " << r.max_deviation << " (" << r.max_deviation_fraction()
          << " of the diagonal " << r.bbox_diagonal << ", +- " << r.hausdorff_error << "; cap " << r.max_deviation_cap
          << "), mean " << r.mean_deviation << "\n";
      out << "written to " << args.output << "; decompose it with: subfab decompose " << args.output << " -o OUTDIR\n";
    }
    std::cout << out.str();
  }
  return kExitOk;
}

void add_repair_options(CLI::App& sub, RepairArgs& args) {
  sub.add_option("MESH", args.mesh, "Input mesh (.obj .off .ply .stl .3mf), any triangle soup")->required();
  sub.add_option("-o,--output", args.output, "Output mesh file (.obj .off .ply .stl)")->required();
  sub.add_option("--max-deviation", args.options.max_deviation,
                 "Cap on the symmetric Hausdorff distance between the result and the input, fraction of the "
                 "bounding-box diagonal; exceeded: exit 2, nothing written")
      ->default_val(args.options.max_deviation)
      ->check(CLI::Range(1e-9, 1.0));
  sub.add_option("--min-piece", args.options.min_component_fraction,
                 "Pieces whose bounding-box diagonal is below this fraction of the largest piece's are removed "
                 "(floating specks); 0 keeps all")
      ->default_val(args.options.min_component_fraction)
      ->check(CLI::Range(0.0, 0.999));
}

const RegisterCommand kRegisterRepair(make_command<RepairArgs>(
    "repair", 12,
    "Turn a triangle soup into a closed, manifold, outward-oriented solid without self-intersections, with "
    "CGAL's repair tools: merge duplicate vertices, drop degenerate and duplicate faces, split pinched "
    "vertices, orient, sew borders, drop small pieces, fill holes with faired patches, resolve "
    "self-intersections (keeping the outer hull), orient outward. Prints what each step found and changed "
    "and the Hausdorff distance to the input; the result passes every check of `subfab info`. Exit 2 (nothing "
    "written) when the mesh cannot be repaired or the deviation exceeds --max-deviation.",
    add_repair_options, run_repair));

}  // namespace
}  // namespace subfab::cli
