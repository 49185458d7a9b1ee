// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/view/write_view_html.h"

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "subfab/core/error.h"
#include "view/encode_base64.h"
#include "view/html_text.h"
#include "view/viewer_js.h"

namespace subfab {
namespace {

using Json = nlohmann::ordered_json;

Json rgb_json(const Rgb& c) { return Json::array({c[0], c[1], c[2]}); }

std::vector<float> flat(const std::vector<Vec3>& points) {
  std::vector<float> out;
  out.reserve(points.size() * 3);
  for (const Vec3& p : points)
    for (int k = 0; k < 3; ++k) out.push_back(static_cast<float>(p[k]));
  return out;
}

Json polygon_json(const ViewPolygon& polygon) {
  if (polygon.loops2d.size() != polygon.loops3d.size() || polygon.loops2d.empty())
    throw InvalidArgumentError("view: a polygon needs as many 2D loops as 3D loops, and at least one");
  std::vector<float> p2;
  std::vector<Vec3> p3;
  Json loops = Json::array();
  for (std::size_t l = 0; l < polygon.loops2d.size(); ++l) {
    if (polygon.loops2d[l].size() != polygon.loops3d[l].size())
      throw InvalidArgumentError("view: a polygon loop has different 2D and 3D corner counts");
    loops.push_back(polygon.loops2d[l].size());
    for (const Eigen::Vector2d& p : polygon.loops2d[l]) {
      p2.push_back(static_cast<float>(p.x()));
      p2.push_back(static_cast<float>(p.y()));
    }
    p3.insert(p3.end(), polygon.loops3d[l].begin(), polygon.loops3d[l].end());
  }
  return {{"loops", loops}, {"p2", detail::base64_float32(p2)}, {"p3", detail::base64_float32(flat(p3))}};
}

Json hex_json(const ViewHexCells& hex) {
  const std::size_t n = hex.cells.size();
  if (hex.colors.size() != n || hex.values.size() != n || (!hex.neighbors.empty() && hex.neighbors.size() != n))
    throw InvalidArgumentError("view: hexahedral cells need one colour, one value and one neighbour set per cell");
  const std::vector<std::array<int, 6>> computed = hex.neighbors.empty() ? hex_face_neighbors(hex.cells)
                                                                         : std::vector<std::array<int, 6>>{};
  const std::vector<std::array<int, 6>>& neighbors = hex.neighbors.empty() ? computed : hex.neighbors;
  std::vector<std::uint32_t> cells, colors, across;
  std::vector<float> values;
  cells.reserve(8 * n);
  across.reserve(6 * n);
  for (std::size_t c = 0; c < n; ++c) {
    for (int v : hex.cells[c]) {
      if (v < 0 || std::size_t(v) >= hex.points.size())
        throw InvalidArgumentError("view: hexahedron " + std::to_string(c) + " has a corner out of range");
      cells.push_back(static_cast<std::uint32_t>(v));
    }
    for (int d : neighbors[c]) across.push_back(static_cast<std::uint32_t>(d));  // -1 -> 0xffffffff
    colors.push_back(static_cast<std::uint32_t>((hex.colors[c][0] << 16) | (hex.colors[c][1] << 8) | hex.colors[c][2]));
    values.push_back(static_cast<float>(hex.values[c]));
  }
  return {{"points", detail::base64_float32(flat(hex.points))},
          {"cells", detail::base64_uint32(cells)},
          {"neighbors", detail::base64_uint32(across)},
          {"colors", detail::base64_uint32(colors)},
          {"values", detail::base64_float32(values)},
          {"label", hex.value_label}};
}

Json object_json(const ViewObject& o) {
  Json j;
  j["name"] = o.name;
  j["style"] = o.style == ViewStyle::Ghost ? "ghost" : "solid";
  j["color"] = rgb_json(o.color);
  j["offset"] = Json::array({o.explode_offset.x(), o.explode_offset.y(), o.explode_offset.z()});
  Json info = Json::array();
  for (const auto& [label, value] : o.info) info.push_back(Json::array({label, value}));
  j["info"] = info;
  if (!o.hex.cells.empty()) {
    j["hex"] = hex_json(o.hex);
  } else if (!o.polygons.empty()) {
    Json polygons = Json::array();
    for (const ViewPolygon& p : o.polygons) polygons.push_back(polygon_json(p));
    j["polygons"] = polygons;
  } else {
    std::vector<std::uint32_t> indices;
    indices.reserve(o.mesh.faces.size() * 3);
    for (const Triangle& t : o.mesh.faces)
      for (int v : t) indices.push_back(static_cast<std::uint32_t>(v));
    j["positions"] = detail::base64_float32(flat(o.mesh.vertices));
    j["indices"] = detail::base64_uint32(indices);
  }
  return j;
}

//! The scene as JSON text safe inside a <script> element.
std::string scene_json(const ViewScene& scene) {
  Json j;
  j["title"] = scene.title;
  j["eye"] = Json::array({scene.towards_eye.x(), scene.towards_eye.y(), scene.towards_eye.z()});
  j["objects"] = Json::array();
  for (const ViewObject& o : scene.objects) j["objects"].push_back(object_json(o));
  std::string text = j.dump();
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') {
      out += "<\\/";
      ++i;
    } else {
      out += text[i];
    }
  }
  return out;
}

const char* const kStyle = R"css(
html, body { margin: 0; height: 100%; overflow: hidden; font: 14px/1.4 system-ui, sans-serif; color: #222; }
#view { position: absolute; left: 0; top: 0; display: block; }
#panel { position: absolute; left: 12px; top: 12px; width: 290px; max-height: calc(100% - 24px); overflow: auto;
         background: rgba(255, 255, 255, 0.92); border-radius: 6px; padding: 10px 14px; box-shadow: 0 1px 4px #0003; }
h1 { font-size: 17px; margin: 0 0 2px; } h2 { font-size: 15px; margin: 6px 0 4px; }
.sub { color: #555; margin-bottom: 8px; } .help { color: #666; font-size: 12px; margin-top: 8px; }
.legend span { display: inline-block; width: 12px; height: 12px; margin-right: 5px; vertical-align: -1px; border-radius: 2px; }
.legend div { display: inline-block; margin-right: 10px; }
input[type=range] { width: 100%; } table { border-collapse: collapse; } th { text-align: left; padding-right: 10px; font-weight: 600; }
#info { margin-top: 8px; border-top: 1px solid #ddd; padding-top: 6px; }
#errors { display: none; position: absolute; right: 12px; bottom: 12px; background: #fdd; color: #700; padding: 8px; white-space: pre-wrap; }
)css";

}  // namespace

std::string read_three_js(const WriteViewOptions& options) {
  std::filesystem::path path = options.three_js_path;
  if (path.empty()) {
    const char* env = std::getenv("SUBFAB_THREE_JS");
    path = env && *env ? std::filesystem::path(env) : std::filesystem::path(kDefaultThreeJsPath);
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (in) text << in.rdbuf();
  if (!in || text.str().empty())
    throw IoError(path.string() +
                  ": cannot read three.js, which view.html inlines; install Debian's libjs-three "
                  "(scripts/setup.sh does), set SUBFAB_THREE_JS to a three.js r111 file, or pass --no-view");
  return text.str();
}

std::string view_html(const ViewScene& scene, const std::string& three_js) {
  using detail::escape_html;
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
       "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; script-src 'unsafe-inline'; "
       "style-src 'unsafe-inline'; img-src data:\">\n"
       "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
       "<title>"
    << escape_html(scene.title) << "</title>\n<style>" << kStyle << "</style></head>\n<body>\n"
    << "<canvas id=\"view\"></canvas>\n<div id=\"panel\">\n<h1>" << escape_html(scene.title) << "</h1>\n"
    << "<div class=\"sub\">" << escape_html(scene.subtitle) << "</div>\n<div class=\"legend\">";
  for (const ViewLegendEntry& e : scene.legend)
    h << "<div><span style=\"background:" << to_hex(e.color) << "\"></span>" << escape_html(e.label) << "</div>";
  h << "</div>\n<label id=\"explode-row\">Explode<input id=\"explode\" type=\"range\" min=\"0\" max=\"100\" "
       "value=\"0\"></label>\n"
    << "<div id=\"cells-row\" style=\"display:none\">\n"
    << "<label>Cut along <select id=\"cut-axis\"><option>x</option><option>y</option><option>z</option></select>"
       " <span id=\"cut-text\"></span><input id=\"cut\" type=\"range\" min=\"0\" max=\"100\" value=\"100\"></label>\n"
    << "<label>Show cells with <span id=\"filter-label\"></span> &le; <span id=\"filter-text\"></span>"
       "<input id=\"filter\" type=\"range\" min=\"0\" max=\"100\" value=\"100\"></label>\n"
    << "<div id=\"cells-count\" class=\"help\"></div>\n</div>\n"
    << "<div id=\"ghost-row\"><label><input id=\"ghost\" type=\"checkbox\" checked> show "
    << escape_html(scene.ghost_label) << " (translucent)</label></div>\n"
    << "<button id=\"reset\" type=\"button\">Reset view</button>\n"
    << "<div id=\"info\">Click a part to see its details.</div>\n"
    << "<div class=\"help\">Drag: rotate &middot; right-drag or shift-drag: pan &middot; wheel: zoom</div>\n"
    << "</div>\n<div id=\"errors\"></div>\n"
    << "<script>/* three.js r111 (MIT licence, https://threejs.org), inlined from Debian's libjs-three */\n"
    << three_js << "\n</script>\n"
    << "<script id=\"subfab-scene\" type=\"application/json\">" << scene_json(scene) << "</script>\n"
    << "<script>\n" << detail::viewer_js() << "</script>\n</body></html>\n";
  return h.str();
}

void write_view_html(const ViewScene& scene, const std::filesystem::path& path, const WriteViewOptions& options) {
  const std::string page = view_html(scene, read_three_js(options));
  std::ofstream out(path, std::ios::binary);
  if (!out) throw IoError(path.string() + ": cannot write");
  out << page;
  if (!out) throw IoError(path.string() + ": write failed (disk full?)");
}

}  // namespace subfab
