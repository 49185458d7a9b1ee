// SPDX-License-Identifier: GPL-3.0-or-later
#include "view/render_picture.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "subfab/core/error.h"
#include "view/encode_base64.h"

namespace subfab::detail {
namespace {

void append_be32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.insert(out.end(), {std::uint8_t(v >> 24), std::uint8_t(v >> 16), std::uint8_t(v >> 8), std::uint8_t(v)});
}

//! Appends a PNG chunk: length, type, data, CRC of type and data (zlib's crc32).
void append_chunk(std::vector<std::uint8_t>& png, const char (&type)[5], const std::vector<std::uint8_t>& data) {
  append_be32(png, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = png.size();
  png.insert(png.end(), type, type + 4);
  png.insert(png.end(), data.begin(), data.end());
  append_be32(png, static_cast<std::uint32_t>(crc32(0L, png.data() + start, static_cast<uInt>(png.size() - start))));
}

//! The z-buffered image being drawn.
struct Canvas {
  int width, height;
  std::vector<float> depth;          // larger = nearer the eye
  std::vector<int> layer;            // -1 = background
  std::vector<std::uint8_t> rgb;
  Canvas(int w, int h)
      : width(w), height(h), depth(std::size_t(w) * h, -std::numeric_limits<float>::infinity()),
        layer(std::size_t(w) * h, -1), rgb(std::size_t(w) * h * 3, 255) {}

  //! Fills the screen-space triangle p (x right, y down, z depth) where it is
  //! nearest. Edge functions in plane form: weight k = e[k] . (x, y, 1) is
  //! the barycentric weight of corner k (its area ratio), so the depth is
  //! linear in x and y too and is stepped along each row.
  void fill(const Vec3 p[3], int id, const Rgb& color) {
    const double twice_area =
        (p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) - (p[1].y() - p[0].y()) * (p[2].x() - p[0].x());
    if (std::abs(twice_area) < 1e-12) return;
    Eigen::Vector3d e[3];
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = p[(k + 1) % 3];
      const Vec3& b = p[(k + 2) % 3];
      e[k] = Eigen::Vector3d(a.y() - b.y(), b.x() - a.x(), a.x() * b.y() - b.x() * a.y()) / twice_area;
    }
    const Eigen::Vector3d zplane = e[0] * p[0].z() + e[1] * p[1].z() + e[2] * p[2].z();
    const int x0 = std::max(0, int(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
    const int x1 = std::min(width - 1, int(std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()}))));
    const int y0 = std::max(0, int(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
    const int y1 = std::min(height - 1, int(std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()}))));
    for (int y = y0; y <= y1; ++y) {
      const Eigen::Vector3d row(x0 + 0.5, y + 0.5, 1.0);
      double w0 = e[0].dot(row), w1 = e[1].dot(row), w2 = e[2].dot(row), z = zplane.dot(row);
      for (int x = x0; x <= x1; ++x, w0 += e[0].x(), w1 += e[1].x(), w2 += e[2].x(), z += zplane.x()) {
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const std::size_t at = std::size_t(y) * width + x;
        if (float(z) <= depth[at]) continue;
        depth[at] = float(z);
        layer[at] = id;
        for (int c = 0; c < 3; ++c) rgb[3 * at + c] = static_cast<std::uint8_t>(color[c]);
      }
    }
  }

  //! Darkens pixels on the border between two layers or a layer and the background.
  void outline() {
    std::vector<std::uint8_t> out = rgb;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const int id = layer[std::size_t(y) * width + x];
        if (id < 0) continue;
        bool edge = false;
        for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= width || ny >= height || layer[std::size_t(ny) * width + nx] != id) edge = true;
        }
        if (edge)
          for (int c = 0; c < 3; ++c) out[3 * (std::size_t(y) * width + x) + c] = 60;
      }
    rgb = std::move(out);
  }
};

}  // namespace

std::vector<std::uint8_t> encode_png_rgb(int width, int height, const std::vector<std::uint8_t>& rgb) {
  std::vector<std::uint8_t> rows;
  rows.reserve((std::size_t(width) * 3 + 1) * height);
  for (int y = 0; y < height; ++y) {
    rows.push_back(0);  // no filter
    rows.insert(rows.end(), rgb.begin() + std::ptrdiff_t(y) * width * 3, rgb.begin() + std::ptrdiff_t(y + 1) * width * 3);
  }
  uLongf size = compressBound(static_cast<uLong>(rows.size()));
  std::vector<std::uint8_t> packed(size);
  if (compress2(packed.data(), &size, rows.data(), static_cast<uLong>(rows.size()), 9) != Z_OK)
    throw AlgorithmError("PNG encoding failed (zlib)");
  packed.resize(size);
  std::vector<std::uint8_t> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<std::uint8_t> header;
  append_be32(header, static_cast<std::uint32_t>(width));
  append_be32(header, static_cast<std::uint32_t>(height));
  header.insert(header.end(), {8, 2, 0, 0, 0});  // 8-bit RGB, deflate, no filter choice, no interlace
  append_chunk(png, "IHDR", header);
  append_chunk(png, "IDAT", packed);
  append_chunk(png, "IEND", {});
  return png;
}

namespace {

//! The layers drawn from `view` (before the outline).
Canvas draw(const std::vector<PictureLayer>& layers, const PictureView& view) {
  const Vec3 eye = view.towards_eye.normalized();
  Vec3 right = view.up.cross(eye);
  if (right.norm() < 1e-9) right = Vec3::UnitX().cross(eye);
  right.normalize();
  const Vec3 up = eye.cross(right);
  BoundingBox screen;  // the frame's corners in (right, up)
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1 ? view.frame.max : view.frame.min).x(), (c & 2 ? view.frame.max : view.frame.min).y(),
                      (c & 4 ? view.frame.max : view.frame.min).z());
    screen.extend(Vec3(corner.dot(right), corner.dot(up), 0));
  }
  const double margin = 0.06;
  const double scale = std::min(view.width * (1 - 2 * margin) / std::max(screen.size().x(), 1e-300),
                                view.height * (1 - 2 * margin) / std::max(screen.size().y(), 1e-300));
  const Vec3 mid = 0.5 * (screen.min + screen.max);
  Canvas canvas(view.width, view.height);
  for (std::size_t l = 0; l < layers.size(); ++l) {
    const Mesh& mesh = *layers[l].mesh;
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
      Vec3 p[3];
      for (int k = 0; k < 3; ++k) {
        const Vec3& v = mesh.vertices[mesh.faces[f][k]];
        p[k] = Vec3(0.5 * view.width + (v.dot(right) - mid.x()) * scale, 0.5 * view.height - (v.dot(up) - mid.y()) * scale,
                    v.dot(eye));
      }
      const double light = 0.45 + 0.55 * std::abs(face_unit_normal(mesh, f).dot(eye));
      Rgb c;
      for (int k = 0; k < 3; ++k) c[k] = std::clamp(int(layers[l].color[k] * light + 0.5), 0, 255);
      canvas.fill(p, int(l), c);
    }
  }
  return canvas;
}

}  // namespace

std::string render_picture(const std::vector<PictureLayer>& layers, const PictureView& view, int highlight) {
  Canvas best = draw(layers, view);
  if (highlight >= 0) {
    // The view (towards_eye mirrored through the axis planes) showing most of the highlighted layer.
    const auto visible = [highlight](const Canvas& c) { return std::count(c.layer.begin(), c.layer.end(), highlight); };
    auto best_count = visible(best);
    for (int m = 1; m < 8; ++m) {
      PictureView mirrored = view;
      for (int k = 0; k < 3; ++k)
        if (m & (1 << k)) mirrored.towards_eye[k] = -mirrored.towards_eye[k];
      Canvas c = draw(layers, mirrored);
      const auto count = visible(c);
      if (count > best_count) {
        best_count = count;
        best = std::move(c);
      }
    }
  }
  best.outline();
  const std::vector<std::uint8_t> png = encode_png_rgb(view.width, view.height, best.rgb);
  return "data:image/png;base64," + encode_base64(png.data(), png.size());
}

}  // namespace subfab::detail
