// SPDX-License-Identifier: GPL-3.0-or-later
//! \file export_unfolding.cpp
//! The unfolding export (stage 7; fabrication output the thesis leaves as
//! future work, Section 3.4): lays the nets out on sheets (layout_sheets.cpp)
//! and writes simplified.obj and unfold.json (here), nets.svg and nets.dxf
//! (write_nets.cpp) and preview.png (write_preview.cpp).
#include "subfab/unfold/export_unfolding.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "subfab/core/error.h"
#include "subfab/unfold/unfold_summary_to_json.h"
#include "unfold/export_format.h"
#include "unfold/triangulate_facets.h"
#include "unfold/write_nets.h"
#include "unfold/write_preview.h"

namespace subfab {

using unfold_detail::Drawing;
using unfold_detail::label_points;
using unfold_detail::make_drawing;
using unfold_detail::num;
using unfold_detail::open_out;
using unfold_detail::short_num;
using unfold_detail::write_dxf;
using unfold_detail::write_preview;
using unfold_detail::write_svg;

namespace {

void write_obj(const PolyMesh& mesh, const Mesh& tri, const std::vector<int>& tri_facet,
               const std::filesystem::path& path) {
  std::ofstream out = open_out(path);
  out << "# subfab unfold: simplified polygonal mesh, one polygon per facet (counter-clockwise from outside);\n"
         "# facets with holes are written as triangles. Facet f is the f-th polygon group 'g facet_f'.\n";
  for (const auto& v : mesh.vertices) out << "v " << num(v.x()) << " " << num(v.y()) << " " << num(v.z()) << "\n";
  std::size_t t = 0;
  for (std::size_t f = 0; f < mesh.num_facets(); ++f) {
    out << "g facet_" << f << "\n";
    if (mesh.facets[f].loops.size() == 1) {
      out << "f";
      for (int v : mesh.facets[f].loops[0]) out << " " << v + 1;
      out << "\n";
    } else {
      for (; t < tri.faces.size() && tri_facet[t] < int(f); ++t) {
      }
      for (; t < tri.faces.size() && tri_facet[t] == int(f); ++t)
        out << "f " << tri.faces[t][0] + 1 << " " << tri.faces[t][1] + 1 << " " << tri.faces[t][2] + 1 << "\n";
    }
  }
  if (!out) throw IoError("cannot write " + path.string());
}

void write_json(const PolyMesh& mesh, const Unfolding& unfolding, const SheetLayout& layout,
                const UnfoldSummary& summary, const nlohmann::ordered_json& input, const std::filesystem::path& path) {
  nlohmann::ordered_json j;
  if (!input.is_null()) j["input"] = input;
  j["facets"] = nlohmann::ordered_json::array();
  for (std::size_t f = 0; f < mesh.num_facets(); ++f) {
    nlohmann::ordered_json facet;
    facet["id"] = f;
    facet["net"] = unfolding.net_of_facet[f];
    auto loop3 = [&](std::size_t l) {
      nlohmann::ordered_json a = nlohmann::ordered_json::array();
      for (int v : mesh.facets[f].loops[l]) a.push_back({mesh.vertices[v].x(), mesh.vertices[v].y(), mesh.vertices[v].z()});
      return a;
    };
    auto loop2 = [&](std::size_t l) {
      nlohmann::ordered_json a = nlohmann::ordered_json::array();
      for (const Vec2& p : layout.positions[f][l]) a.push_back({p.x(), p.y()});
      return a;
    };
    facet["vertices3d"] = loop3(0);
    facet["vertices2d"] = loop2(0);
    if (mesh.facets[f].loops.size() > 1) {
      facet["holes3d"] = nlohmann::ordered_json::array();
      facet["holes2d"] = nlohmann::ordered_json::array();
      for (std::size_t l = 1; l < mesh.facets[f].loops.size(); ++l) {
        facet["holes3d"].push_back(loop3(l));
        facet["holes2d"].push_back(loop2(l));
      }
    }
    j["facets"].push_back(facet);
  }
  j["folds"] = nlohmann::ordered_json::array();
  for (const Fold& f : unfolding.folds) {
    nlohmann::ordered_json fold;
    fold["facets"] = {f.parent, f.child};
    fold["dihedral_deg"] = f.dihedral_deg;
    fold["vbit_deg"] = vbit_angle_deg(f.dihedral_deg);
    fold["side"] = vbit_side(f.dihedral_deg);
    j["folds"].push_back(fold);
  }
  j["summary"] = unfold_summary_to_json(summary);
  std::ofstream out = open_out(path);
  out << j.dump(1) << "\n";
  if (!out) throw IoError("cannot write " + path.string());
}

}  // namespace

double vbit_angle_deg(double dihedral_deg) { return std::abs(180.0 - dihedral_deg); }
const char* vbit_side(double dihedral_deg) { return dihedral_deg < 180.0 ? "back" : "top"; }

void export_unfolding(const PolyMesh& mesh, const Unfolding& unfolding, const UnfoldSummary& summary,
                      const std::filesystem::path& outdir, const ExportUnfoldingOptions& options) {
  StageScope scope(options.progress, "export");
  std::error_code ec;
  std::filesystem::create_directories(outdir, ec);
  if (ec) throw IoError("cannot create folder " + outdir.string() + ": " + ec.message());
  const SheetLayout layout = layout_sheets(unfolding, options);
  if (options.progress && !layout.oversized_nets.empty())
    options.progress->warn(std::to_string(layout.oversized_nets.size()) +
                           " net(s) do not fit on one sheet; use a larger --sheet");
  std::vector<int> tri_facet;
  const Mesh tri = unfold_detail::triangulate_facets(mesh, &tri_facet);
  const Drawing drawing = make_drawing(mesh, unfolding, layout, label_points(mesh, layout, tri, tri_facet));
  write_obj(mesh, tri, tri_facet, outdir / "simplified.obj");
  write_svg(drawing, layout, outdir / "nets.svg");
  write_dxf(drawing, layout, outdir / "nets.dxf");
  write_json(mesh, unfolding, layout, summary, options.input, outdir / "unfold.json");
  write_preview(mesh, tri, tri_facet, drawing, layout, unfolding, options, outdir / "preview.png");
  if (options.progress)
    options.progress->info("wrote " + std::to_string(layout.num_sheets) + " sheet(s) of " +
                           short_num(layout.sheet_width) + " x " + short_num(layout.sheet_height) + " to " +
                           outdir.string());
}

}  // namespace subfab
