// SPDX-License-Identifier: GPL-3.0-or-later
#include "view/render_picture.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "subfab/core/parallel.h"
#include "subfab/core/write_png.h"
#include "view/encode_base64.h"

namespace subfab::detail {
namespace {

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

//! The orthographic projection of a view: screen x right, y down, z towards the eye.
struct Projection {
  Vec3 eye, right, up, mid;
  double scale = 1;
  int width = 1, height = 1;

  explicit Projection(const PictureView& view) : width(view.width), height(view.height) {
    eye = view.towards_eye.normalized();
    right = view.up.cross(eye);
    if (right.norm() < 1e-9) right = Vec3::UnitX().cross(eye);
    right.normalize();
    up = eye.cross(right);
    BoundingBox screen;  // the frame's corners in (right, up)
    for (int c = 0; c < 8; ++c) {
      const Vec3 corner((c & 1 ? view.frame.max : view.frame.min).x(), (c & 2 ? view.frame.max : view.frame.min).y(),
                        (c & 4 ? view.frame.max : view.frame.min).z());
      screen.extend(Vec3(corner.dot(right), corner.dot(up), 0));
    }
    const double margin = 0.06;
    scale = std::min(width * (1 - 2 * margin) / std::max(screen.size().x(), 1e-300),
                     height * (1 - 2 * margin) / std::max(screen.size().y(), 1e-300));
    mid = 0.5 * (screen.min + screen.max);
  }

  //! Draws `mesh` into `canvas` as layer `id`, flat shaded in `color`.
  void draw(Canvas& canvas, const Mesh& mesh, int id, const Rgb& color) const {
    std::vector<Vec3> points;
    points.reserve(mesh.num_vertices());
    for (const Vec3& v : mesh.vertices)
      points.emplace_back(0.5 * width + (v.dot(right) - mid.x()) * scale, 0.5 * height - (v.dot(up) - mid.y()) * scale,
                          v.dot(eye));
    for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
      const Vec3 p[3] = {points[mesh.faces[f][0]], points[mesh.faces[f][1]], points[mesh.faces[f][2]]};
      const Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]);  // screen space: its z over its length is the light
      const double light = 0.45 + 0.55 * std::abs(n.z()) / std::max(n.norm(), 1e-300);
      Rgb c;
      for (int k = 0; k < 3; ++k) c[k] = std::clamp(int(color[k] * light + 0.5), 0, 255);
      canvas.fill(p, id, c);
    }
  }
};

std::vector<std::uint8_t> outlined_png(Canvas canvas) {
  canvas.outline();
  RgbImage image(canvas.width, canvas.height);
  image.pixels = std::move(canvas.rgb);
  return encode_png(image);
}

std::string png_data_uri(Canvas canvas) {
  const std::vector<std::uint8_t> png = outlined_png(std::move(canvas));
  return "data:image/png;base64," + encode_base64(png.data(), png.size());
}

//! The eye direction mirrored through the axis planes whose bits are set in m.
Vec3 mirrored(const Vec3& eye, int m) {
  Vec3 out = eye;
  for (int k = 0; k < 3; ++k)
    if (m & (1 << k)) out[k] = -out[k];
  return out;
}

}  // namespace

std::vector<std::uint8_t> render_png(const std::vector<PictureLayer>& layers, const PictureView& view) {
  const Projection projection(view);
  Canvas canvas(view.width, view.height);
  for (std::size_t l = 0; l < layers.size(); ++l) projection.draw(canvas, *layers[l].mesh, int(l), layers[l].color);
  return outlined_png(std::move(canvas));
}

std::string render_picture(const std::vector<PictureLayer>& layers, const PictureView& view) {
  const std::vector<std::uint8_t> png = render_png(layers, view);
  return "data:image/png;base64," + encode_base64(png.data(), png.size());
}

struct AssemblyPictures::Views {
  std::vector<Projection> full, draft;  // per mirror 0..7
  std::vector<Canvas> full_canvas, draft_canvas;
};

AssemblyPictures::AssemblyPictures(const PictureView& view, const Rgb& placed_color)
    : views_(std::make_unique<Views>()), placed_color_(placed_color) {
  PictureView draft = view;
  draft.width = std::max(16, view.width / 4);
  draft.height = std::max(16, view.height / 4);
  for (int m = 0; m < 8; ++m) {
    PictureView full = view;
    full.towards_eye = draft.towards_eye = mirrored(view.towards_eye, m);
    views_->full.emplace_back(full);
    views_->draft.emplace_back(draft);
    views_->full_canvas.emplace_back(full.width, full.height);
    views_->draft_canvas.emplace_back(draft.width, draft.height);
  }
}

AssemblyPictures::~AssemblyPictures() = default;

std::string AssemblyPictures::add(const Mesh& mesh, const Rgb& color) {
  const int id = num_added_++;
  // The view showing most of the new mesh, compared on drafts (1/4 of the size).
  int best = 0;
  std::ptrdiff_t best_count = -1;
  for (int m = 0; m < 8; ++m) {
    Canvas c = views_->draft_canvas[m];
    views_->draft[m].draw(c, mesh, id, color);
    const std::ptrdiff_t count = std::count(c.layer.begin(), c.layer.end(), id);
    if (count > best_count) {
      best_count = count;
      best = m;
    }
  }
  Canvas picture = views_->full_canvas[best];
  views_->full[best].draw(picture, mesh, id, color);
  // Then the mesh joins the placed ones, in grey.
  parallel_for(0, 8, [&](std::size_t m) {
    views_->draft[m].draw(views_->draft_canvas[m], mesh, id, placed_color_);
    views_->full[m].draw(views_->full_canvas[m], mesh, id, placed_color_);
  });
  return png_data_uri(std::move(picture));
}

}  // namespace subfab::detail
