// SPDX-License-Identifier: GPL-3.0-or-later
//! `subfab info MESH [--json]`: measures of a mesh and the result of every
//! input check. Exit 0 whatever the checks say (the problems are listed);
//! 2 when the file cannot be read as a mesh at all.
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "command.h"
#include "subfab/checks/analyze_mesh.h"
#include "subfab/checks/report_to_json.h"
#include "subfab/mesh/read_mesh.h"

namespace subfab::cli {
namespace {

struct InfoArgs {
  std::string mesh;
  CommonOptions common;
};

std::string number(double x) {
  std::ostringstream out;
  out << std::setprecision(6) << x;
  return out.str();
}

std::string vec(const Vec3& v) {
  return "(" + number(v.x()) + ", " + number(v.y()) + ", " + number(v.z()) + ")";
}

template <typename T>
std::string optional_text(const std::optional<T>& value, const std::string& unknown) {
  if (!value) return unknown;
  if constexpr (std::is_same_v<T, double>)
    return number(*value);
  else
    return std::to_string(*value);
}

void print_table(const std::string& path, const ReadInfo& read, const MeshReport& r) {
  std::ostringstream out;
  const auto row = [&](const std::string& key, const std::string& value) {
    out << "  " << std::left << std::setw(20) << key << value << "\n";
  };
  out << path << " (" << format_name(read.format) << ")\n";
  row("vertices", std::to_string(r.num_vertices));
  row("faces", std::to_string(r.num_faces));
  row("edges", std::to_string(r.num_edges));
  if (read.polygons_triangulated > 0)
    row("triangulated", std::to_string(read.polygons_triangulated) + " polygons");
  if (r.bbox && !r.bbox->is_empty()) {
    row("bbox min", vec(r.bbox->min));
    row("bbox max", vec(r.bbox->max));
    const Vec3 size = r.bbox->size();
    row("size", number(size.x()) + " x " + number(size.y()) + " x " + number(size.z()));
  } else {
    row("bbox", "unknown (coordinates are not finite)");
  }
  row("diagonal", optional_text(r.diagonal, "unknown"));
  row("average edge", optional_text(r.average_edge_length, "unknown"));
  row("area", optional_text(r.area, "unknown"));
  row("volume", optional_text(r.volume, "unknown (not closed)"));
  row("components", std::to_string(r.num_components));
  row("genus", optional_text(r.genus, "unknown (not a closed, manifold, oriented mesh)"));
  out << "checks\n";
  std::size_t num_failed = 0;
  for (const auto& check : r.checks) {
    const char* tag = check.passed() ? "PASS" : (check.failed() ? "FAIL" : "SKIP");
    num_failed += check.failed() ? 1 : 0;
    out << "  " << tag << "  " << std::left << std::setw(24) << check.name << check.message << "\n";
  }
  // The reader's remarks: dropped unreferenced vertices, welded STL corners, ...
  for (const auto& note : read.notes) out << "note: " << note << "\n";
  if (num_failed == 0)
    out << "all checks passed: usable as a closed solid\n";
  else
    out << num_failed << (num_failed == 1 ? " check" : " checks")
        << " failed: commands that need a closed solid (decompose, unfold) will refuse this mesh\n";
  std::cout << out.str();
}

int run_info(const InfoArgs& args) {
  ReadInfo read;
  const Mesh mesh = read_mesh(args.mesh, &read);  // IoError / InvalidMeshError: exit 2
  const MeshReport report = analyze_mesh(mesh);
  if (args.common.json) {
    nlohmann::json json = report_to_json(report);
    json["file"] = args.mesh;
    json["format"] = format_name(read.format);
    json["notes"] = read.notes;
    std::cout << json.dump(2) << "\n";
  } else {
    print_table(args.mesh, read, report);
  }
  return kExitOk;
}

void add_info_options(CLI::App& sub, InfoArgs& args) {
  sub.add_option("MESH", args.mesh, "Mesh file (.obj .off .ply .stl .3mf)")->required();
}

const RegisterCommand kRegisterInfo(make_command<InfoArgs>(
    "info", 10,
    "Print a mesh's measures (counts, bounding box, area, volume, components, genus) and the "
    "result of every input check. Exit 0 even when checks fail (they are listed); 2 when the "
    "file cannot be read as a mesh.",
    add_info_options, run_info));

}  // namespace
}  // namespace subfab::cli
