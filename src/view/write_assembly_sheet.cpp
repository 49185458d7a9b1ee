// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/view/write_assembly_sheet.h"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "subfab/core/error.h"
#include "subfab/core/parallel.h"
#include "view/html_text.h"
#include "view/render_picture.h"

namespace subfab {

using detail::escape_html;
using detail::format_number;

namespace {

const char* const kStyle = R"css(
body { font: 13px/1.4 system-ui, sans-serif; color: #222; margin: 18px; }
h1 { font-size: 20px; margin: 0 0 4px; } h2 { font-size: 16px; margin: 18px 0 6px; } h3 { font-size: 14px; margin: 0 0 6px; }
table { border-collapse: collapse; } td, th { padding: 2px 10px 2px 0; text-align: left; vertical-align: top; }
table.list td, table.list th { border-bottom: 1px solid #ddd; }
.swatch { display: inline-block; width: 11px; height: 11px; border-radius: 2px; margin-right: 4px; vertical-align: -1px; }
.step { display: flex; gap: 14px; border: 1px solid #ccc; border-radius: 6px; padding: 8px; margin: 8px 0;
        break-inside: avoid; page-break-inside: avoid; }
figure { margin: 0; text-align: center; font-size: 11px; color: #555; } figure img { display: block; border: 1px solid #eee; }
.note { color: #555; }
@media print { body { margin: 0; } .step { border-color: #999; } }
)css";

//! Records the page's state for the browser tests (as view.html does).
const char* const kStatusScript = R"js(
window.subfabStatus = { frames: 0, errors: [], ready: true };
window.addEventListener('error', function (e) { window.subfabStatus.errors.push(String(e.message)); });
document.addEventListener('securitypolicyviolation', function (e) { window.subfabStatus.errors.push('blocked: ' + e.blockedURI); });
requestAnimationFrame(function () { window.subfabStatus.frames++; });
)js";

std::string duration_text(double seconds) {
  if (seconds < 0) return "unknown (run subfab mill)";
  const long s = std::lround(seconds);
  std::ostringstream t;
  if (s >= 3600) t << s / 3600 << " h " << (s % 3600) / 60 << " min";
  else t << s / 60 << " min " << s % 60 << " s";
  return t.str();
}

std::string size_text(const Vec3& size, const std::string& unit) {
  return format_number(size.x(), 4) + " &times; " + format_number(size.y(), 4) + " &times; " +
         format_number(size.z(), 4) + " " + unit;
}

Vec3 axis_vector(int axis) {
  Vec3 v = Vec3::Zero();
  v[axis / 2] = axis % 2 == 0 ? 1.0 : -1.0;
  return v;
}

}  // namespace

AssemblySheet assembly_sheet(const DecompositionFolder& folder, const MillInfo* mill, const AssemblySheetOptions& options) {
  if (options.size_mm < 0 || options.mm_per_unit < 0 || !std::isfinite(options.size_mm) || !std::isfinite(options.mm_per_unit))
    throw InvalidArgumentError("assembly sheet: --size and --scale must be positive numbers");
  const std::size_t n = folder.blocks.size();
  BoundingBox all;
  std::vector<Mesh> meshes(n);
  GluingOptions glue;
  glue.rotation = folder.rotation;
  glue.resolution = options.resolution;
  for (std::size_t i = 0; i < n; ++i) {
    const DecompositionBlock& b = folder.blocks[i];
    all.extend(b.bbox.min);
    all.extend(b.bbox.max);
    meshes[i] = b.mesh;
    glue.preferred_axis.push_back(axis_index(b.axis));
    glue.volumes.push_back(b.volume);
  }
  AssemblySheet sheet;
  std::string scale_source;
  if (options.mm_per_unit > 0) {
    sheet.mm_per_unit = options.mm_per_unit;
    scale_source = "--scale";
  } else if (options.size_mm > 0 && !all.is_empty()) {
    sheet.mm_per_unit = options.size_mm / all.size().maxCoeff();
    scale_source = "--size " + format_number(options.size_mm) + " mm";
  } else if (mill && mill->mm_per_unit > 0) {
    sheet.mm_per_unit = mill->mm_per_unit;
    scale_source = "mill.json";
  }
  const bool stock_from_mill =
      mill && (scale_source == "mill.json" || std::abs(sheet.mm_per_unit - mill->mm_per_unit) <= 1e-9 * sheet.mm_per_unit);
  if (mill && !stock_from_mill && options.progress)
    options.progress->warn("assembly sheet: the scale (" + scale_source + ") differs from mill.json's (" +
                           format_number(mill->mm_per_unit) + " mm per unit); stock sizes are the blocks' bounding "
                           "boxes at the given scale, without mill.json's stock margin");
  const std::string unit = sheet.mm_per_unit > 0 ? "mm" : "model units";
  const double to_unit = sheet.mm_per_unit > 0 ? sheet.mm_per_unit : 1.0;

  sheet.plan = plan_gluing_order(meshes, glue);
  std::vector<std::size_t> step_of(n);
  for (std::size_t s = 0; s < sheet.plan.steps.size(); ++s) step_of[sheet.plan.steps[s].block] = s;

  // Per block: stock size, time, colour.
  std::vector<Vec3> stock(n);
  std::vector<double> time(n, -1);
  std::vector<std::string> gcode(n);
  std::vector<Rgb> color(n);
  for (std::size_t i = 0; i < n; ++i) {
    const DecompositionBlock& b = folder.blocks[i];
    stock[i] = b.stock_size * to_unit;
    color[i] = direction_color(b.axis);
    if (mill) {
      auto it = mill->blocks.find(b.id);
      if (it != mill->blocks.end()) {
        if (stock_from_mill && it->second.stock_mm.norm() > 0) stock[i] = it->second.stock_mm;
        time[i] = it->second.time_s;
        gcode[i] = it->second.gcode;
      }
    }
    if (time[i] >= 0) sheet.total_time_s = std::max(0.0, sheet.total_time_s) + time[i];
  }

  // Pictures: the block alone, and with the blocks glued before it.
  std::vector<std::string> alone(n), placed(n);
  parallel_for(0, n, [&](std::size_t i) {
    detail::PictureView view;
    view.width = view.height = options.picture_size;
    view.frame = folder.blocks[i].bbox;
    alone[i] = detail::render_picture({{&folder.blocks[i].mesh, color[i]}}, view);
  });
  detail::PictureView whole;
  whole.width = whole.height = options.picture_size;
  whole.frame = all;
  detail::AssemblyPictures assembly(whole, {205, 205, 205});
  for (const GluingStep& step : sheet.plan.steps)
    placed[step.block] = assembly.add(folder.blocks[step.block].mesh, color[step.block]);

  const bool rotated = !folder.rotation.isIdentity(1e-12);
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
       "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; script-src 'unsafe-inline'; "
       "style-src 'unsafe-inline'; img-src data:\">\n<title>Assembly sheet: "
    << escape_html(folder.input_path) << "</title>\n<style>" << kStyle << "</style>\n<script>" << kStatusScript
    << "</script></head>\n<body>\n<h1>Assembly sheet: " << escape_html(folder.input_path) << "</h1>\n<p>" << n
    << " blocks. Sizes in " << unit;
  if (sheet.mm_per_unit > 0)
    h << " (" << format_number(sheet.mm_per_unit, 5) << " mm per model unit, from " << escape_html(scale_source) << ")";
  else
    h << " (give <code>--size</code>, <code>--scale</code> or <code>--mill</code> for millimetres)";
  h << ". Stock sizes: width &times; depth &times; height, the height along the milling direction"
    << (stock_from_mill ? ", from mill.json (with its stock margin)" : ", the block's bounding box (no margin)") << ".";
  if (sheet.total_time_s >= 0) h << " Total machining time: " << duration_text(sheet.total_time_s) << ".";
  h << "</p>\n<h2>Cut list</h2>\n<table class=\"list\"><tr><th>Block</th><th>Stock</th><th>Milling direction</th>"
       "<th>Machining time</th><th>G-code</th><th>Volume</th><th>Glued at step</th></tr>\n";
  for (std::size_t i = 0; i < n; ++i) {
    const DecompositionBlock& b = folder.blocks[i];
    h << "<tr><td>" << b.id << "</td><td>" << size_text(stock[i], unit) << "</td><td><span class=\"swatch\" style=\"background:"
      << to_hex(color[i]) << "\"></span>" << escape_html(b.axis) << "</td><td>" << duration_text(time[i]) << "</td><td>"
      << escape_html(gcode[i].empty() ? "-" : gcode[i]) << "</td><td>" << format_number(b.volume * std::pow(to_unit, 3), 4)
      << " " << unit << "&sup3;</td><td>" << step_of[i] + 1 << "</td></tr>\n";
  }
  h << "</table>\n<h2>Gluing order</h2>\n<p class=\"note\">Glue the blocks in this order. Each one slides into place "
       "from the side named, moving straight towards the model, without passing through a block glued before it "
       "(checked on rays "
    << format_number(sheet.plan.ray_spacing * to_unit, 3) << " " << unit
    << " apart). Sides are the axes of the decomposition frame, the frame of the milling directions"
    << (rotated ? " (the input rotated by decomposition.json's \"rotation\"; the vector is in input coordinates)" : "")
    << ". Pictures: the block, and the model so far (grey) with the block in place.</p>\n";
  if (!sheet.plan.stuck.empty())
    h << "<p><b>" << sheet.plan.stuck.size()
      << " blocks interlock: no single straight move puts one of them in place among the others. Put them "
         "together as a group first.</b></p>\n";
  for (std::size_t s = 0; s < sheet.plan.steps.size(); ++s) {
    const GluingStep& step = sheet.plan.steps[s];
    const std::size_t i = step.block;
    const DecompositionBlock& b = folder.blocks[i];
    std::string how;
    if (step.axis >= 0) {
      const int opposite = step.axis ^ 1;
      how = "slide in from the " + axis_label(step.axis) + " side, moving along " + axis_label(opposite);
      if (rotated) {
        const Vec3 v = folder.rotation.transpose() * axis_vector(opposite);
        how += " (" + format_number(v.x(), 3) + ", " + format_number(v.y(), 3) + ", " + format_number(v.z(), 3) + ")";
      }
    } else {
      how = sheet.plan.stuck.empty() ? "first block: lay it down" : "interlocked group: assemble together";
    }
    h << "<div class=\"step\"><figure><img alt=\"block " << b.id << "\" width=\"" << options.picture_size
      << "\" height=\"" << options.picture_size << "\" src=\"" << alone[i] << "\"><figcaption>block " << b.id
      << "</figcaption></figure><figure><img alt=\"block " << b.id << " in place\" width=\"" << options.picture_size
      << "\" height=\"" << options.picture_size << "\" src=\"" << placed[i]
      << "\"><figcaption>in place</figcaption></figure>\n<div><h3>Step " << s + 1 << ": block " << b.id
      << "</h3><table><tr><th>Glue</th><td>" << escape_html(how) << "</td></tr><tr><th>Stock</th><td>"
      << size_text(stock[i], unit) << "</td></tr><tr><th>Milling direction</th><td><span class=\"swatch\" style=\"background:"
      << to_hex(color[i]) << "\"></span>" << escape_html(b.axis) << "</td></tr><tr><th>Machining time</th><td>"
      << duration_text(time[i]) << "</td></tr>";
    if (!gcode[i].empty()) h << "<tr><th>G-code</th><td>" << escape_html(gcode[i]) << "</td></tr>";
    h << "</table></div></div>\n";
  }
  h << "</body></html>\n";
  sheet.html = h.str();
  return sheet;
}

AssemblySheet write_assembly_sheet(const std::filesystem::path& outdir, const AssemblySheetOptions& options) {
  const DecompositionFolder folder = read_decomposition(outdir);
  MillInfo mill;
  if (!options.mill_dir.empty()) mill = read_mill_info(options.mill_dir);
  AssemblySheet sheet = assembly_sheet(folder, options.mill_dir.empty() ? nullptr : &mill, options);
  const std::filesystem::path path = outdir / "assembly.html";
  std::ofstream out(path, std::ios::binary);
  if (!out) throw IoError(path.string() + ": cannot write");
  out << sheet.html;
  if (!out) throw IoError(path.string() + ": write failed (disk full?)");
  return sheet;
}

}  // namespace subfab
