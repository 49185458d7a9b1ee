// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/view/write_decomposition_view.h"

#include <map>
#include <optional>

#include "view/html_text.h"

namespace subfab {

using detail::format_number;

namespace {

Vec3 centre(const BoundingBox& b) { return 0.5 * (b.min + b.max); }

//! The direction colour, a little darker for every other block of the same
//! direction, so neighbours of one direction stay apart (same hue).
Rgb block_color(const std::string& axis, int rank) {
  const Rgb base = direction_color(axis);
  const double factor = 1.0 - 0.14 * (rank % 3);
  return {int(base[0] * factor + 0.5), int(base[1] * factor + 0.5), int(base[2] * factor + 0.5)};
}

std::string vector_text(const Vec3& v) {
  return "(" + format_number(v.x(), 3) + ", " + format_number(v.y(), 3) + ", " + format_number(v.z(), 3) + ")";
}

}  // namespace

ViewScene decomposition_scene(const DecompositionFolder& folder, const Mesh* model) {
  ViewScene scene;
  scene.title = "subfab decomposition: " + std::to_string(folder.blocks.size()) + " blocks";
  scene.subtitle = folder.input_path.empty() ? folder.folder.string() : folder.input_path;
  scene.ghost_label = folder.model_label;
  BoundingBox all;
  double total_volume = 0;
  for (const DecompositionBlock& b : folder.blocks) {
    all.extend(b.bbox.min);
    all.extend(b.bbox.max);
    total_volume += b.volume;
  }
  const Vec3 middle = centre(all);
  if (model) {
    ViewObject ghost;
    ghost.name = scene.ghost_label;
    ghost.style = ViewStyle::Ghost;
    ghost.color = {150, 150, 150};
    ghost.mesh = *model;
    scene.objects.push_back(std::move(ghost));
  }
  std::map<std::string, int> rank;
  for (const DecompositionBlock& b : folder.blocks) {
    ViewObject o;
    o.name = "block " + std::to_string(b.id);
    o.color = block_color(b.axis, rank[b.axis]++);
    o.mesh = b.mesh;
    o.explode_offset = centre(b.bbox) - middle;
    o.info = {{"Number", std::to_string(b.id)},
              {"Milling direction", b.axis + " " + vector_text(b.direction)},
              {"Stock size", format_number(b.stock_size.x()) + " x " + format_number(b.stock_size.y()) + " x " +
                                 format_number(b.stock_size.z()) + " (model units, height last)"},
              {"Volume", format_number(b.volume) + " (" + format_number(100.0 * b.volume / total_volume, 3) +
                             " % of the blocks)"},
              {"Triangles", std::to_string(b.mesh.num_faces())}};
    if (b.max_overhang_deg > 0.1) o.info.emplace_back("Steepest overhang", format_number(b.max_overhang_deg, 3) + " deg");
    scene.objects.push_back(std::move(o));
  }
  for (const char* axis : {"+x", "-x", "+y", "-y", "+z", "-z"})
    if (rank.count(axis)) scene.legend.push_back({std::string("mill ") + axis, direction_color(axis)});
  return scene;
}

void write_decomposition_view(const std::filesystem::path& outdir, const DecompositionViewOptions& options) {
  const DecompositionFolder folder = read_decomposition(outdir);
  std::optional<Mesh> read;
  const Mesh* model = options.model;
  if (!model) {
    std::string note;
    read = read_decomposed_model(folder, &note);
    if (read) model = &*read;
    else if (options.progress) options.progress->warn("view.html shows the blocks only: " + note);
  }
  write_view_html(decomposition_scene(folder, model), outdir / "view.html", options.html);
}

}  // namespace subfab
