// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/view/write_hex_mesh_view.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "subfab/core/error.h"
#include "view/html_text.h"
#include "view/render_picture.h"

namespace subfab {

using detail::format_number;

namespace {

//! A pure hue (degrees in [0, 360)) at full saturation and value.
Rgb pure_hue(double hue) {
  const double h = hue / 60.0;
  const int sector = int(std::floor(h)) % 6;
  const int rising = int(std::lround(255 * (h - std::floor(h))));
  switch (sector) {
    case 0: return {255, rising, 0};
    case 1: return {255 - rising, 255, 0};
    case 2: return {0, 255, rising};
    case 3: return {0, 255 - rising, 255};
    case 4: return {rising, 0, 255};
    default: return {255, 0, 255 - rising};
  }
}

//! Bin of hexmesh.json's histogram: 0 for <= 0, then b for ((b-1)/10, b/10].
int quality_bin(double sj) {
  if (!(sj > 0)) return 0;
  return std::clamp(int(std::ceil(sj * 10 - 1e-12)), 1, 10);
}

void check_arrays(const HexCellArrays& a, const char* what) {
  for (std::size_t c = 0; c < a.cells.size(); ++c)
    for (int v : a.cells[c])
      if (v < 0 || std::size_t(v) >= a.points.size())
        throw InvalidArgumentError(std::string("hex mesh view: ") + what + " cell " + std::to_string(c) +
                                   " has a corner out of range");
}

//! The boundary faces (no neighbour) of the cells, two triangles each, in
//! the mesh's vertex numbering; face_cell[t] = the cell of triangle t.
Mesh boundary_mesh(const HexCellArrays& a, const std::vector<std::array<int, 6>>& neighbors,
                   std::vector<int>* face_cell = nullptr) {
  Mesh m;
  m.vertices = a.points;
  for (std::size_t c = 0; c < a.cells.size(); ++c)
    for (int f = 0; f < 6; ++f) {
      if (neighbors[c][f] >= 0) continue;
      const auto& q = kViewHexFaces[f];
      m.faces.push_back({a.cells[c][q[0]], a.cells[c][q[1]], a.cells[c][q[2]]});
      m.faces.push_back({a.cells[c][q[0]], a.cells[c][q[2]], a.cells[c][q[3]]});
      if (face_cell) face_cell->insert(face_cell->end(), 2, int(c));
    }
  return m;
}

//! Screen-right direction of a view from `towards_eye` with y up (as the
//! browser view and the rasteriser set it).
Vec3 screen_right(const Vec3& towards_eye) {
  Vec3 right = Vec3::UnitY().cross(towards_eye.normalized());
  if (right.norm() < 1e-9) right = Vec3::UnitX().cross(towards_eye.normalized());
  return right.normalized();
}

//! The translation that puts `points` right of `beside` on the screen, a
//! quarter of beside's screen width apart, their centres level.
Vec3 offset_beside(const std::vector<Vec3>& beside, const std::vector<Vec3>& points, const Vec3& right) {
  if (beside.empty() || points.empty()) return Vec3::Zero();
  double b_lo = INFINITY, b_hi = -INFINITY, p_lo = INFINITY, p_hi = -INFINITY;
  Vec3 b_mid = Vec3::Zero(), p_mid = Vec3::Zero();
  for (const Vec3& v : beside) b_lo = std::min(b_lo, v.dot(right)), b_hi = std::max(b_hi, v.dot(right)), b_mid += v;
  for (const Vec3& v : points) p_lo = std::min(p_lo, v.dot(right)), p_hi = std::max(p_hi, v.dot(right)), p_mid += v;
  b_mid /= double(beside.size());
  p_mid /= double(points.size());
  Vec3 across = b_mid - p_mid;
  across -= across.dot(right) * right;  // level the centres
  return across + (b_hi + 0.25 * (b_hi - b_lo) - p_lo) * right;
}

std::vector<Vec3> moved(std::vector<Vec3> points, const Vec3& by) {
  for (Vec3& p : points) p += by;
  return points;
}

void check_view(const HexMeshView& view) {
  if (view.scaled_jacobian.size() != view.mesh.cells.size())
    throw InvalidArgumentError("hex mesh view: " + std::to_string(view.scaled_jacobian.size()) +
                               " scaled Jacobians for " + std::to_string(view.mesh.cells.size()) + " cells");
  check_arrays(view.mesh, "mesh");
  check_arrays(view.structure, "structure");
}

}  // namespace

Rgb quality_color(double sj) {
  const int bin = quality_bin(sj);
  if (bin == 0) return {255, 0, 255};
  return pure_hue(220.0 * (bin - 1) / 9.0);
}

std::vector<ViewLegendEntry> quality_legend() {
  std::vector<ViewLegendEntry> legend{{"inverted (<= 0)", quality_color(-1)}};
  for (int b = 1; b <= 10; ++b)
    legend.push_back({format_number((b - 1) / 10.0) + "-" + format_number(b / 10.0), quality_color((b - 0.5) / 10.0)});
  return legend;
}

ViewScene hex_mesh_scene(const HexMeshView& view) {
  check_view(view);
  ViewScene scene;
  const std::size_t n = view.mesh.cells.size();
  scene.title = "subfab hexmesh: " + std::to_string(n) + " hexahedra";
  double lo = INFINITY, sum = 0;
  for (double sj : view.scaled_jacobian) lo = std::min(lo, sj), sum += sj;
  scene.subtitle = (view.input_name.empty() ? std::string() : view.input_name + ": ") + "cells coloured by scaled Jacobian" +
                   (n ? " (min " + format_number(lo, 3) + ", avg " + format_number(sum / double(n), 3) + ")" : "");
  scene.legend = quality_legend();
  scene.ghost_label = "input surface";
  if (view.input) {
    ViewObject ghost;
    ghost.name = scene.ghost_label;
    ghost.style = ViewStyle::Ghost;
    ghost.color = {150, 150, 150};
    ghost.mesh = *view.input;
    scene.objects.push_back(std::move(ghost));
  }
  ViewObject cells;
  cells.name = "hexahedral mesh";
  cells.hex.points = view.mesh.points;
  cells.hex.cells = view.mesh.cells;
  cells.hex.values = view.scaled_jacobian;
  cells.hex.value_label = "Scaled Jacobian";
  cells.hex.colors.reserve(n);
  for (double sj : view.scaled_jacobian) cells.hex.colors.push_back(quality_color(sj));
  cells.hex.neighbors = hex_face_neighbors(view.mesh.cells);
  cells.info = {{"Hexahedra", std::to_string(n)}, {"Vertices", std::to_string(view.mesh.points.size())}};
  scene.objects.push_back(std::move(cells));
  if (!view.structure.cells.empty()) {
    ViewObject core;
    core.name = "tubular structure";
    core.color = {170, 170, 178};
    HexCellArrays placed = view.structure;
    placed.points = moved(placed.points, offset_beside(view.mesh.points, placed.points, screen_right(scene.towards_eye)));
    core.mesh = boundary_mesh(placed, hex_face_neighbors(placed.cells));
    core.info = {{"What", "the conforming core of cubes (branch and end nodes) and tubes (arcs), before padding, "
                          "subdivision and projection (thesis D.3); drawn beside the mesh"},
                 {"Hexahedra", std::to_string(placed.cells.size())}};
    scene.objects.push_back(std::move(core));
  }
  return scene;
}

void write_hex_mesh_view(const HexMeshView& view, const std::filesystem::path& path, const WriteViewOptions& options) {
  write_view_html(hex_mesh_scene(view), path, options);
}

std::vector<std::uint8_t> hex_mesh_preview_png(const HexMeshView& view, const HexMeshPreviewOptions& options) {
  check_view(view);
  std::vector<int> face_cell;
  const Mesh boundary = boundary_mesh(view.mesh, hex_face_neighbors(view.mesh.cells), &face_cell);
  // One layer per quality bin present (its faces in the bin's colour), then the structure.
  std::vector<Mesh> meshes(11);
  for (Mesh& m : meshes) m.vertices = boundary.vertices;
  for (std::size_t t = 0; t < boundary.faces.size(); ++t)
    meshes[std::size_t(quality_bin(view.scaled_jacobian[std::size_t(face_cell[t])]))].faces.push_back(boundary.faces[t]);
  detail::PictureView picture;
  picture.width = options.width;
  picture.height = options.height;
  picture.towards_eye = options.towards_eye;
  std::vector<detail::PictureLayer> layers;
  for (int b = 0; b <= 10; ++b)
    if (!meshes[std::size_t(b)].faces.empty()) layers.push_back({&meshes[std::size_t(b)], quality_color(b == 0 ? -1 : (b - 0.5) / 10)});
  for (const Vec3& p : view.mesh.points) picture.frame.extend(p);
  Mesh core;
  if (!view.structure.cells.empty()) {
    HexCellArrays placed = view.structure;
    placed.points = moved(placed.points, offset_beside(view.mesh.points, placed.points, screen_right(options.towards_eye)));
    core = boundary_mesh(placed, hex_face_neighbors(placed.cells));
    for (const Vec3& p : placed.points) picture.frame.extend(p);
    layers.push_back({&core, {170, 170, 178}});
  }
  if (layers.empty()) picture.frame.extend(Vec3::Zero());
  return detail::render_png(layers, picture);
}

void write_hex_mesh_preview(const HexMeshView& view, const std::filesystem::path& path,
                            const HexMeshPreviewOptions& options) {
  const std::vector<std::uint8_t> png = hex_mesh_preview_png(view, options);
  std::ofstream out(path, std::ios::binary);
  if (!out) throw IoError(path.string() + ": cannot write");
  out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
  if (!out) throw IoError(path.string() + ": write failed (disk full?)");
}

}  // namespace subfab
