// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/view/write_unfolding_view.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

#include "subfab/core/error.h"
#include "view/html_text.h"

namespace subfab {

using detail::format_number;

namespace {

using Json = nlohmann::json;

//! A colour per net: hues a golden angle apart, mid saturation.
Rgb net_color(int net) {
  const double h = std::fmod(net * 137.50776405, 360.0) / 60.0, s = 0.55, v = 0.88;
  const double c = v * s, x = c * (1 - std::abs(std::fmod(h, 2.0) - 1)), m = v - c;
  double r = 0, g = 0, b = 0;
  switch (int(h)) {
    case 0: r = c, g = x; break;
    case 1: r = x, g = c; break;
    case 2: g = c, b = x; break;
    case 3: g = x, b = c; break;
    case 4: r = x, b = c; break;
    default: r = c, b = x; break;
  }
  return {int((r + m) * 255 + 0.5), int((g + m) * 255 + 0.5), int((b + m) * 255 + 0.5)};
}

struct Facet {
  int id = 0, net = 0;
  std::vector<std::vector<Vec3>> loops3d;
  std::vector<std::vector<Eigen::Vector2d>> loops2d;
};

std::vector<Vec3> loop3(const Json& j) {
  std::vector<Vec3> out;
  for (const Json& p : j) out.emplace_back(p.at(0).get<double>(), p.at(1).get<double>(), p.at(2).get<double>());
  return out;
}

std::vector<Eigen::Vector2d> loop2(const Json& j) {
  std::vector<Eigen::Vector2d> out;
  for (const Json& p : j) out.emplace_back(p.at(0).get<double>(), p.at(1).get<double>());
  return out;
}

std::vector<Facet> read_facets(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path.string() + ": cannot read; is the folder written by `subfab unfold`?");
  std::vector<Facet> facets;
  try {
    const Json doc = Json::parse(in);
    for (const Json& f : doc.at("facets")) {
      Facet facet;
      facet.id = f.at("id").get<int>();
      facet.net = f.at("net").get<int>();
      facet.loops3d.push_back(loop3(f.at("vertices3d")));
      facet.loops2d.push_back(loop2(f.at("vertices2d")));
      if (f.contains("holes3d"))
        for (std::size_t h = 0; h < f.at("holes3d").size(); ++h) {
          facet.loops3d.push_back(loop3(f.at("holes3d").at(h)));
          facet.loops2d.push_back(loop2(f.at("holes2d").at(h)));
        }
      for (std::size_t l = 0; l < facet.loops3d.size(); ++l)
        if (facet.loops3d[l].size() != facet.loops2d[l].size() || facet.loops3d[l].size() < 3)
          throw IoError(path.string() + ": facet " + std::to_string(facet.id) + " has mismatched 3D and sheet corners");
      facets.push_back(std::move(facet));
    }
  } catch (const nlohmann::json::exception& e) {
    throw IoError(path.string() + ": malformed (" + e.what() + "); run `subfab unfold` again");
  }
  return facets;
}

//! Newell's normal of a loop: its direction is the loop's normal, its length twice its area.
Vec3 newell(const std::vector<Vec3>& loop) {
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0; i < loop.size(); ++i) n += loop[i].cross(loop[(i + 1) % loop.size()]);
  return n;
}

}  // namespace

ViewScene unfolding_scene(const std::filesystem::path& outdir, const Mesh* input) {
  const std::vector<Facet> facets = read_facets(outdir / "unfold.json");
  ViewScene scene;
  int num_nets = 0;
  BoundingBox model, sheet;
  for (const Facet& f : facets) {
    num_nets = std::max(num_nets, f.net + 1);
    for (const Vec3& p : f.loops3d[0]) model.extend(p);
    for (const auto& p : f.loops2d[0]) sheet.extend(Vec3(p.x(), p.y(), 0));
  }
  scene.title = "subfab unfolding: " + std::to_string(facets.size()) + " facets, " + std::to_string(num_nets) + " nets";
  scene.subtitle = "left: the simplified model; right: its nets as cut from the sheet (same colour = same net)";
  scene.towards_eye = Vec3(0.2, 0.25, 1.0);  // from the front: the sheet faces +z
  if (input) {
    ViewObject ghost;
    ghost.name = "input model";
    ghost.style = ViewStyle::Ghost;
    ghost.color = {150, 150, 150};
    ghost.mesh = *input;
    scene.objects.push_back(std::move(ghost));
  }
  if (facets.empty()) return scene;
  // The sheet stands upright (x right, y up) right of the model, facing +z.
  const double gap = 0.15 * model.diagonal();
  const Vec3 sheet_origin(model.max.x() + gap, model.min.y(), 0.5 * (model.min.z() + model.max.z()));
  const double explode = 0.15 * model.diagonal();
  std::vector<ViewObject> flat;
  for (const Facet& f : facets) {
    Vec3 normal = newell(f.loops3d[0]);
    double area = 0.5 * normal.norm();
    for (std::size_t l = 1; l < f.loops3d.size(); ++l) area -= 0.5 * newell(f.loops3d[l]).norm();
    normal.normalize();
    ViewObject o;
    o.name = "facet " + std::to_string(f.id);
    o.color = net_color(f.net);
    o.polygons.push_back({f.loops2d, f.loops3d});
    o.explode_offset = explode * normal;
    o.info = {{"Facet", std::to_string(f.id)},
              {"Net", std::to_string(f.net)},
              {"Area", format_number(area) + " (model units^2)"},
              {"Normal", "(" + format_number(normal.x(), 3) + ", " + format_number(normal.y(), 3) + ", " +
                             format_number(normal.z(), 3) + ")"},
              {"Corners", std::to_string(f.loops3d[0].size()) +
                              (f.loops3d.size() > 1 ? " and " + std::to_string(f.loops3d.size() - 1) + " hole(s)" : "")}};
    ViewObject n = o;
    n.name = "facet " + std::to_string(f.id) + " on the sheet";
    n.explode_offset = Vec3::Zero();
    for (auto& loop : n.polygons[0].loops3d) loop.clear();
    for (std::size_t l = 0; l < f.loops2d.size(); ++l)
      for (const auto& p : f.loops2d[l])
        n.polygons[0].loops3d[l].push_back(sheet_origin + Vec3(p.x() - sheet.min.x(), p.y() - sheet.min.y(), 0));
    scene.objects.push_back(std::move(o));
    flat.push_back(std::move(n));
  }
  for (ViewObject& n : flat) scene.objects.push_back(std::move(n));
  for (int net = 0; net < std::min(num_nets, 12); ++net) scene.legend.push_back({"net " + std::to_string(net), net_color(net)});
  return scene;
}

void write_unfolding_view(const std::filesystem::path& outdir, const UnfoldingViewOptions& options) {
  write_view_html(unfolding_scene(outdir, options.input), outdir / "view.html", options.html);
}

}  // namespace subfab
