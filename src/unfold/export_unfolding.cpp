// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/unfold/export_unfolding.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "subfab/core/error.h"
#include "subfab/unfold/unfold_summary_to_json.h"
#include "unfold/triangulate_facets.h"
#include "unfold/write_png.h"

namespace subfab {

using unfold_detail::RgbImage;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string num(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string short_num(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

std::ofstream open_out(const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw IoError("cannot write " + path.string() + ": check that the folder is writable");
  return out;
}

// One line of the drawing: a cut or a fold.
struct Segment {
  Vec2 a, b;
  int kind;  // 0 cut, 1 fold top, 2 fold back
  std::string label;
};

struct Label {
  Vec2 at;
  std::string text;
};

struct Drawing {
  std::vector<Segment> segments;
  std::vector<Label> facet_labels;
  double text_size = 1;
};

std::uint64_t key_of(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// Interior point of each facet in the layout: centroid of its largest triangle.
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
    folds[key_of(f.v0, f.v1)] = &f;
    fold_edges.insert(key_of(f.v0, f.v1));
    fold_edges.insert(key_of(f.v1, f.v0));
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
        const auto it = folds.find(key_of(u, v));
        if (it != folds.end() && it->second->parent == int(f)) {
          const double dih = it->second->dihedral_deg;
          const int kind = dih < 180.0 ? 2 : 1;
          char text[64];
          std::snprintf(text, sizeof text, "V%.1f %s", vbit_angle_deg(dih), vbit_side(dih));
          d.segments.push_back({a, b, kind, text});
        } else if (!fold_edges.count(key_of(u, v))) {
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
                const UnfoldSummary& summary, const std::filesystem::path& path) {
  nlohmann::ordered_json j;
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

// ---------------------------------------------------------------- preview

std::array<std::uint8_t, 3> palette(int i) {
  static const std::uint8_t colors[][3] = {{141, 211, 199}, {255, 255, 179}, {190, 186, 218}, {251, 128, 114},
                                           {128, 177, 211}, {253, 180, 98},  {179, 222, 105}, {252, 205, 229},
                                           {217, 217, 217}, {188, 128, 189}, {204, 235, 197}, {255, 237, 111}};
  const auto& c = colors[((i % 12) + 12) % 12];
  return {c[0], c[1], c[2]};
}

void fill_triangle(RgbImage& img, std::vector<float>* zbuf, std::vector<int>* ids, const Vec3 p[3], int id,
                   std::array<std::uint8_t, 3> color, int x_lo, int x_hi) {
  const double minx = std::max<double>(x_lo, std::floor(std::min({p[0].x(), p[1].x(), p[2].x()})));
  const double maxx = std::min<double>(x_hi - 1, std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()})));
  const double miny = std::max(0.0, std::floor(std::min({p[0].y(), p[1].y(), p[2].y()})));
  const double maxy = std::min<double>(img.height - 1, std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()})));
  const double area = (p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) - (p[1].y() - p[0].y()) * (p[2].x() - p[0].x());
  if (std::abs(area) < 1e-12) return;
  for (int y = int(miny); y <= int(maxy); ++y)
    for (int x = int(minx); x <= int(maxx); ++x) {
      const double px = x + 0.5, py = y + 0.5;
      double w[3];
      for (int k = 0; k < 3; ++k) {
        const Vec3& a = p[(k + 1) % 3];
        const Vec3& b = p[(k + 2) % 3];
        w[k] = ((b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px - a.x())) / area;
      }
      if (w[0] < 0 || w[1] < 0 || w[2] < 0) continue;
      const std::size_t idx = std::size_t(y) * img.width + x;
      if (zbuf) {
        const float z = static_cast<float>(w[0] * p[0].z() + w[1] * p[1].z() + w[2] * p[2].z());
        if (z <= (*zbuf)[idx]) continue;
        (*zbuf)[idx] = z;
      }
      if (ids) (*ids)[idx] = id;
      img.set(x, y, color[0], color[1], color[2]);
    }
}

void draw_line(RgbImage& img, Vec2 a, Vec2 b, std::array<std::uint8_t, 3> c) {
  const int n = static_cast<int>(std::ceil(std::max(std::abs(b.x() - a.x()), std::abs(b.y() - a.y())))) + 1;
  for (int i = 0; i <= n; ++i) {
    const Vec2 p = a + (b - a) * (double(i) / n);
    img.set(int(std::floor(p.x())), int(std::floor(p.y())), c[0], c[1], c[2]);
  }
}

void write_preview(const PolyMesh& mesh, const Mesh& tri, const std::vector<int>& tri_facet, const Drawing& drawing,
                   const SheetLayout& layout, const Unfolding& unfolding, const ExportUnfoldingOptions& options,
                   const std::filesystem::path& path) {
  const int W = std::max(64, options.preview_width), H = std::max(64, options.preview_height);
  RgbImage img(W, H, 255);
  const int half = W / 2;
  // Left: the model, orthographic view from (1, 0.8, 1.3), z-buffered, flat shaded.
  const Vec3 view = Vec3(1.0, 0.8, 1.3).normalized();
  Vec3 right = Vec3::UnitY().cross(view);
  if (right.norm() < 1e-6) right = Vec3::UnitX();
  right.normalize();
  const Vec3 up = view.cross(right);
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const auto& v : mesh.vertices) {
    const Vec3 q(v.dot(right), v.dot(up), v.dot(view));
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  const double margin = 0.06;
  const double scale3 = std::min(half * (1 - 2 * margin) / std::max(hi.x() - lo.x(), 1e-30),
                                 H * (1 - 2 * margin) / std::max(hi.y() - lo.y(), 1e-30));
  auto to_screen = [&](const Vec3& v) {
    const Vec3 q(v.dot(right), v.dot(up), v.dot(view));
    return Vec3(half * 0.5 + (q.x() - 0.5 * (lo.x() + hi.x())) * scale3, H * 0.5 - (q.y() - 0.5 * (lo.y() + hi.y())) * scale3,
                q.z());
  };
  std::vector<float> zbuf(std::size_t(W) * H, -std::numeric_limits<float>::infinity());
  std::vector<int> ids(std::size_t(W) * H, -1);
  const Vec3 light = Vec3(0.4, 0.9, 0.7).normalized();
  for (std::size_t t = 0; t < tri.faces.size(); ++t) {
    Vec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = to_screen(tri.vertices[tri.faces[t][k]]);
    const Vec3 n = face_unit_normal(tri, t);
    const double shade = 0.35 + 0.65 * std::max(0.0, n.dot(light));
    auto base = palette(mesh.facets[tri_facet[t]].normal);
    std::array<std::uint8_t, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = static_cast<std::uint8_t>(std::clamp(base[k] * shade, 0.0, 255.0));
    fill_triangle(img, &zbuf, &ids, p, tri_facet[t], c, 0, half);
  }
  for (int y = 0; y + 1 < H; ++y)
    for (int x = 0; x + 1 < half; ++x) {
      const int id = ids[std::size_t(y) * W + x];
      if (id != ids[std::size_t(y) * W + x + 1] || id != ids[std::size_t(y + 1) * W + x]) img.set(x, y, 40, 40, 40);
    }
  // Right: the sheets with the nets.
  const double total_w = layout.num_sheets * (layout.sheet_width + layout.gap) - layout.gap;
  const double scale2 =
      std::min((W - half) * (1 - 2 * margin) / std::max(total_w, 1e-30), H * (1 - 2 * margin) / std::max(layout.sheet_height, 1e-30));
  auto to_sheet = [&](const Vec2& p) {
    return Vec2(half + (W - half) * margin + p.x() * scale2, H * 0.5 + layout.sheet_height * scale2 * 0.5 - p.y() * scale2);
  };
  for (std::size_t t = 0; t < tri.faces.size(); ++t) {
    const int f = tri_facet[t];
    Vec3 p[3];
    for (int k = 0; k < 3; ++k) {
      const int v = tri.faces[t][k];
      for (std::size_t l = 0; l < mesh.facets[f].loops.size(); ++l)
        for (std::size_t i = 0; i < mesh.facets[f].loops[l].size(); ++i)
          if (mesh.facets[f].loops[l][i] == v) {
            const Vec2 s = to_sheet(layout.positions[f][l][i]);
            p[k] = Vec3(s.x(), s.y(), 0);
          }
    }
    auto c = palette(unfolding.net_of_facet[f] + 3);
    fill_triangle(img, nullptr, nullptr, p, f, c, half, W);
  }
  for (int s = 0; s < layout.num_sheets; ++s) {
    const double x0 = s * (layout.sheet_width + layout.gap);
    const Vec2 c[4] = {to_sheet({x0, 0}), to_sheet({x0 + layout.sheet_width, 0}),
                       to_sheet({x0 + layout.sheet_width, layout.sheet_height}), to_sheet({x0, layout.sheet_height})};
    for (int i = 0; i < 4; ++i) draw_line(img, c[i], c[(i + 1) % 4], {160, 160, 160});
  }
  const std::array<std::uint8_t, 3> colors[] = {{0, 0, 0}, {210, 0, 0}, {0, 60, 210}};
  for (const Segment& s : drawing.segments) draw_line(img, to_sheet(s.a), to_sheet(s.b), colors[s.kind]);
  for (int y = 0; y < H; ++y) img.set(half, y, 200, 200, 200);
  unfold_detail::write_png(img, path);
}

}  // namespace

double vbit_angle_deg(double dihedral_deg) { return std::abs(180.0 - dihedral_deg); }
const char* vbit_side(double dihedral_deg) { return dihedral_deg < 180.0 ? "back" : "top"; }

SheetLayout layout_sheets(const Unfolding& unfolding, const ExportUnfoldingOptions& options) {
  SheetLayout layout;
  layout.positions = unfolding.positions;
  const std::size_t num_nets = unfolding.nets.size();
  layout.net_sheet.assign(num_nets, 0);
  std::vector<Vec2> size(num_nets);
  double sum_area = 0, max_w = 0;
  for (std::size_t n = 0; n < num_nets; ++n) {
    const Net& net = unfolding.nets[n];
    // candidate rotations: align an edge with x
    std::vector<double> angles{0.0};
    for (int f : net.facets)
      for (const auto& loop : unfolding.positions[f])
        for (std::size_t i = 0; i < loop.size() && angles.size() < 64; ++i) {
          const Vec2 d = loop[(i + 1) % loop.size()] - loop[i];
          angles.push_back(-std::atan2(d.y(), d.x()));
        }
    double best_area = std::numeric_limits<double>::infinity(), best_angle = 0;
    for (double a : angles) {
      const double c = std::cos(a), s = std::sin(a);
      Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);
      for (int f : net.facets)
        for (const auto& loop : unfolding.positions[f])
          for (const Vec2& p : loop) {
            const Vec2 q(c * p.x() - s * p.y(), s * p.x() + c * p.y());
            lo = lo.cwiseMin(q);
            hi = hi.cwiseMax(q);
          }
      Vec2 ext = hi - lo;
      if (ext.y() > ext.x()) ext = Vec2(ext.y(), ext.x());  // prefer landscape (rotated below)
      const double area = ext.x() * ext.y();
      if (area < best_area * (1 - 1e-9)) {
        best_area = area;
        best_angle = a;
      }
    }
    const double c = std::cos(best_angle), s = std::sin(best_angle);
    Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);
    for (int f : net.facets)
      for (auto& loop : layout.positions[f])
        for (Vec2& p : loop) {
          p = Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y());
          lo = lo.cwiseMin(p);
          hi = hi.cwiseMax(p);
        }
    if (hi.y() - lo.y() > hi.x() - lo.x()) {  // landscape: rotate by -90 degrees
      for (int f : net.facets)
        for (auto& loop : layout.positions[f])
          for (Vec2& p : loop) p = Vec2(p.y(), -p.x());
      lo = Vec2::Constant(1e300);
      hi = Vec2::Constant(-1e300);
      for (int f : net.facets)
        for (const auto& loop : layout.positions[f])
          for (const Vec2& p : loop) {
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
          }
    }
    for (int f : net.facets)
      for (auto& loop : layout.positions[f])
        for (Vec2& p : loop) p -= lo;
    size[n] = hi - lo;
    sum_area += size[n].x() * size[n].y();
    max_w = std::max(max_w, size[n].x());
  }
  layout.gap = 0.03 * std::sqrt(std::max(sum_area, 1e-300));
  const double g = layout.gap;
  double W = options.sheet_width, H = options.sheet_height;
  if (W <= 0) W = std::max(max_w + 2 * g, 1.4 * std::sqrt(sum_area) + 2 * g);
  const bool unbounded = H <= 0;
  std::vector<std::size_t> order(num_nets);
  for (std::size_t i = 0; i < num_nets; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return size[a].y() > size[b].y(); });
  std::vector<Vec2> offset(num_nets);
  int sheet = 0;
  double x = g, y = g, row_h = 0, max_y = 0;
  for (std::size_t n : order) {
    const Vec2 e = size[n];
    if (e.x() + 2 * g > W || (!unbounded && e.y() + 2 * g > H)) layout.oversized_nets.push_back(int(n));
    if (x > g && x + e.x() + g > W) {  // next row
      x = g;
      y += row_h + g;
      row_h = 0;
    }
    if (!unbounded && y > g && y + e.y() + g > H) {  // next sheet
      ++sheet;
      x = g;
      y = g;
      row_h = 0;
    }
    offset[n] = Vec2(sheet * (W + g) + x, y);
    layout.net_sheet[n] = sheet;
    x += e.x() + g;
    row_h = std::max(row_h, e.y());
    max_y = std::max(max_y, y + e.y() + g);
  }
  layout.num_sheets = num_nets ? sheet + 1 : 0;
  layout.sheet_width = W;
  layout.sheet_height = unbounded ? max_y : H;
  for (std::size_t n = 0; n < num_nets; ++n)
    for (int f : unfolding.nets[n].facets)
      for (auto& loop : layout.positions[f])
        for (Vec2& p : loop) p += offset[n];
  return layout;
}

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
  write_json(mesh, unfolding, layout, summary, outdir / "unfold.json");
  write_preview(mesh, tri, tri_facet, drawing, layout, unfolding, options, outdir / "preview.png");
  if (options.progress)
    options.progress->info("wrote " + std::to_string(layout.num_sheets) + " sheet(s) of " +
                           short_num(layout.sheet_width) + " x " + short_num(layout.sheet_height) + " to " +
                           outdir.string());
}

}  // namespace subfab
