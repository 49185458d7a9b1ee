// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_nets.cpp
//! The nets drawing and its SVG and DXF writers (export stage 7; nets of
//! thesis Section 3.3.3, fabrication output left as future work in Section
//! 3.4): every facet edge of the layout is a cut, or a fold drawn once and
//! labelled with its V-bit angle and side.
#include "unfold/write_nets.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "subfab/core/error.h"
#include "unfold/edge_key.h"
#include "unfold/export_format.h"

namespace subfab::unfold_detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

std::vector<Vec2> label_points(const PolyMesh& mesh, const SheetLayout& layout, const Mesh& tri,
                               const std::vector<int>& tri_facet) {
  std::vector<Vec2> at(mesh.num_facets(), Vec2::Zero());
  std::vector<double> best(mesh.num_facets(), -1);
  for (std::size_t t = 0; t < tri.faces.size(); ++t) {
    const int f = tri_facet[t];
    Vec2 p[3];
    for (int k = 0; k < 3; ++k) {
      const int v = tri.faces[t][k];
      for (std::size_t l = 0; l < mesh.facets[f].loops.size(); ++l)
        for (std::size_t i = 0; i < mesh.facets[f].loops[l].size(); ++i)
          if (mesh.facets[f].loops[l][i] == v) p[k] = layout.positions[f][l][i];
    }
    const double area = std::abs((p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x());
    if (area > best[f]) {
      best[f] = area;
      at[f] = (p[0] + p[1] + p[2]) / 3.0;
    }
  }
  return at;
}

Drawing make_drawing(const PolyMesh& mesh, const Unfolding& unfolding, const SheetLayout& layout,
                     const std::vector<Vec2>& label_at) {
  Drawing d;
  std::map<std::uint64_t, const Fold*> folds;  // directed edge in the parent's loop -> fold
  std::set<std::uint64_t> fold_edges;
  for (const Fold& f : unfolding.folds) {
    folds[edge_key(f.v0, f.v1)] = &f;
    fold_edges.insert(edge_key(f.v0, f.v1));
    fold_edges.insert(edge_key(f.v1, f.v0));
  }
  double total_len = 0;
  std::size_t num_edges = 0;
  for (std::size_t f = 0; f < mesh.num_facets(); ++f)
    for (std::size_t l = 0; l < mesh.facets[f].loops.size(); ++l) {
      const auto& loop = mesh.facets[f].loops[l];
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const int u = loop[i], v = loop[(i + 1) % loop.size()];
        const Vec2 a = layout.positions[f][l][i], b = layout.positions[f][l][(i + 1) % loop.size()];
        total_len += (b - a).norm();
        ++num_edges;
        const auto it = folds.find(edge_key(u, v));
        if (it != folds.end() && it->second->parent == int(f)) {
          const double dih = it->second->dihedral_deg;
          const int kind = dih < 180.0 ? 2 : 1;
          char text[64];
          std::snprintf(text, sizeof text, "V%.1f %s", vbit_angle_deg(dih), vbit_side(dih));
          d.segments.push_back({a, b, kind, text});
        } else if (!fold_edges.count(edge_key(u, v))) {
          d.segments.push_back({a, b, 0, ""});
        }
      }
    }
  d.text_size = num_edges ? 0.12 * total_len / double(num_edges) : 1.0;
  for (std::size_t f = 0; f < mesh.num_facets(); ++f) d.facet_labels.push_back({label_at[f], std::to_string(f)});
  return d;
}

void write_svg(const Drawing& d, const SheetLayout& layout, const std::filesystem::path& path) {
  const double total_w = layout.num_sheets * (layout.sheet_width + layout.gap);
  const double total_h = layout.sheet_height;
  auto Y = [&](double y) { return total_h - y; };
  std::ofstream out = open_out(path);
  const double stroke = d.text_size * 0.08;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(total_w) << "\" height=\"" << num(total_h)
      << "\" viewBox=\"" << num(-layout.gap) << " 0 " << num(total_w + layout.gap) << " " << num(total_h) << "\">\n";
  out << "<!-- subfab unfold: model units; sheet outlines, cut lines, folds cut from the top (red) and from the back "
         "(blue, dashed), labels: fold 'V<angle> <side>', facet ids -->\n";
  out << "<g id=\"sheets\" fill=\"none\" stroke=\"#999999\" stroke-width=\"" << num(stroke) << "\">\n";
  for (int s = 0; s < layout.num_sheets; ++s)
    out << "<rect x=\"" << num(s * (layout.sheet_width + layout.gap)) << "\" y=\"0\" width=\""
        << num(layout.sheet_width) << "\" height=\"" << num(layout.sheet_height) << "\"/>\n";
  out << "</g>\n";
  const char* ids[] = {"cut", "fold_top", "fold_back"};
  const char* colors[] = {"#000000", "#d00000", "#0040d0"};
  for (int kind = 0; kind < 3; ++kind) {
    out << "<g id=\"" << ids[kind] << "\" fill=\"none\" stroke=\"" << colors[kind] << "\" stroke-width=\""
        << num(stroke) << "\"" << (kind == 2 ? " stroke-dasharray=\"" + num(4 * stroke) + "," + num(2 * stroke) + "\"" : "")
        << ">\n";
    for (const Segment& s : d.segments)
      if (s.kind == kind)
        out << "<line x1=\"" << num(s.a.x()) << "\" y1=\"" << num(Y(s.a.y())) << "\" x2=\"" << num(s.b.x())
            << "\" y2=\"" << num(Y(s.b.y())) << "\"/>\n";
    out << "</g>\n";
  }
  out << "<g id=\"fold_labels\" font-family=\"sans-serif\" font-size=\"" << num(0.7 * d.text_size)
      << "\" text-anchor=\"middle\" fill=\"#505050\">\n";
  for (const Segment& s : d.segments)
    if (s.kind != 0) {
      const Vec2 m = 0.5 * (s.a + s.b);
      double angle = std::atan2(-(s.b.y() - s.a.y()), s.b.x() - s.a.x()) * 180 / kPi;
      if (angle > 90) angle -= 180;
      if (angle < -90) angle += 180;
      out << "<text x=\"" << num(m.x()) << "\" y=\"" << num(Y(m.y())) << "\" transform=\"rotate(" << short_num(angle)
          << " " << num(m.x()) << " " << num(Y(m.y())) << ")\" dy=\"" << num(-0.3 * d.text_size) << "\">" << s.label
          << "</text>\n";
    }
  out << "</g>\n<g id=\"facet_ids\" font-family=\"sans-serif\" font-size=\"" << num(d.text_size)
      << "\" text-anchor=\"middle\" fill=\"#000000\">\n";
  for (const Label& l : d.facet_labels)
    out << "<text x=\"" << num(l.at.x()) << "\" y=\"" << num(Y(l.at.y()) + 0.35 * d.text_size) << "\">" << l.text
        << "</text>\n";
  out << "</g>\n</svg>\n";
  if (!out) throw IoError("cannot write " + path.string());
}

void write_dxf(const Drawing& d, const SheetLayout& layout, const std::filesystem::path& path) {
  std::ofstream out = open_out(path);
  auto pair = [&](int code, const std::string& value) { out << code << "\n" << value << "\n"; };
  const char* layers[] = {"CUT", "FOLD_TOP", "FOLD_BACK", "LABELS", "SHEETS"};
  const int colors[] = {7, 1, 5, 8, 9};
  pair(999, "subfab unfold nets (model units)");
  pair(0, "SECTION");
  pair(2, "TABLES");
  pair(0, "TABLE");
  pair(2, "LAYER");
  pair(70, "5");
  for (int i = 0; i < 5; ++i) {
    pair(0, "LAYER");
    pair(2, layers[i]);
    pair(70, "0");
    pair(62, std::to_string(colors[i]));
    pair(6, i == 2 ? "DASHED" : "CONTINUOUS");
  }
  pair(0, "ENDTAB");
  pair(0, "ENDSEC");
  pair(0, "SECTION");
  pair(2, "ENTITIES");
  auto line = [&](const char* layer, const Vec2& a, const Vec2& b) {
    pair(0, "LINE");
    pair(8, layer);
    pair(10, num(a.x()));
    pair(20, num(a.y()));
    pair(30, "0.0");
    pair(11, num(b.x()));
    pair(21, num(b.y()));
    pair(31, "0.0");
  };
  auto text = [&](const Vec2& at, double height, double angle, const std::string& s) {
    pair(0, "TEXT");
    pair(8, "LABELS");
    pair(10, num(at.x()));
    pair(20, num(at.y()));
    pair(30, "0.0");
    pair(40, num(height));
    pair(1, s);
    pair(50, short_num(angle));
    pair(72, "1");  // centred
    pair(11, num(at.x()));
    pair(21, num(at.y()));
    pair(31, "0.0");
  };
  for (int s = 0; s < layout.num_sheets; ++s) {
    const double x0 = s * (layout.sheet_width + layout.gap);
    const Vec2 c[4] = {{x0, 0}, {x0 + layout.sheet_width, 0}, {x0 + layout.sheet_width, layout.sheet_height},
                       {x0, layout.sheet_height}};
    for (int i = 0; i < 4; ++i) line("SHEETS", c[i], c[(i + 1) % 4]);
  }
  for (const Segment& s : d.segments) line(layers[s.kind], s.a, s.b);
  for (const Segment& s : d.segments)
    if (s.kind != 0) {
      double angle = std::atan2(s.b.y() - s.a.y(), s.b.x() - s.a.x()) * 180 / kPi;
      if (angle > 90) angle -= 180;
      if (angle < -90) angle += 180;
      text(0.5 * (s.a + s.b), 0.7 * d.text_size, angle, s.label);
    }
  for (const Label& l : d.facet_labels) text(l.at, d.text_size, 0, l.text);
  pair(0, "ENDSEC");
  pair(0, "EOF");
  if (!out) throw IoError("cannot write " + path.string());
}

}  // namespace subfab::unfold_detail
