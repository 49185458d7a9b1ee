// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_preview.cpp
//! preview.png of the unfolding export (stage 7, after thesis Chapter 3):
//! a small z-buffered rasteriser for the model view and the sheets view.
#include "unfold/write_preview.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "subfab/core/write_png.h"

namespace subfab::unfold_detail {

namespace {

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

}  // namespace

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
  subfab::write_png(img, path);
}

}  // namespace subfab::unfold_detail
