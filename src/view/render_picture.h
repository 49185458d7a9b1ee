// SPDX-License-Identifier: GPL-3.0-or-later
//! \file render_picture.h
//! Private: pictures drawn here (an orthographic z-buffered rasteriser, flat
//! two-sided shading, a dark outline around each mesh): the small pictures of
//! blocks assembly.html embeds as PNG data URIs (so the sheet prints without
//! a script), and hexmesh's preview.png.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "subfab/view/view_scene.h"

namespace subfab::detail {

//! One mesh of a picture, in one colour.
struct PictureLayer {
  const Mesh* mesh = nullptr;
  Rgb color{200, 200, 200};
};

//! What the picture looks at.
struct PictureView {
  Vec3 towards_eye = Vec3(0.55, 0.45, 0.70);  // direction from the model to the eye (input frame; normalised here)
  Vec3 up = Vec3::UnitY();                     // projected to the picture's vertical
  BoundingBox frame;                           // what must fit in the picture (input frame)
  int width = 220, height = 220;               // pixels
};

//! Renders the layers (layer l drawn as outline region l); returns the PNG bytes.
std::vector<std::uint8_t> render_png(const std::vector<PictureLayer>& layers, const PictureView& view);

//! Renders the layers; returns "data:image/png;base64,...".
std::string render_picture(const std::vector<PictureLayer>& layers, const PictureView& view);

//! Pictures of an assembly growing one mesh at a time: add() returns the
//! meshes added before in `placed_color` with the new one in its colour,
//! seen from the direction (view.towards_eye mirrored through the axis
//! planes, 8 candidates) that shows most of the new one (ties: the first,
//! unmirrored one). The placed meshes are kept drawn, once per candidate, so
//! n meshes cost O(n) drawing, not O(n^2).
class AssemblyPictures {
 public:
  AssemblyPictures(const PictureView& view, const Rgb& placed_color);
  ~AssemblyPictures();
  AssemblyPictures(const AssemblyPictures&) = delete;
  AssemblyPictures& operator=(const AssemblyPictures&) = delete;
  std::string add(const Mesh& mesh, const Rgb& color);

 private:
  struct Views;
  std::unique_ptr<Views> views_;
  Rgb placed_color_;
  int num_added_ = 0;
};

}  // namespace subfab::detail
