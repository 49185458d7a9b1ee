// SPDX-License-Identifier: GPL-3.0-or-later
//! \file view_scene.h
//! What the browser view (view.html) shows, independent of where it comes
//! from: a list of objects (a decomposition's blocks, an unfolding's facets,
//! later a hex mesh's cells), each a triangle mesh or a set of planar
//! polygons, with a colour, an explode offset and the lines a click on it
//! shows. write_view_html() turns a scene into one self-contained HTML file.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! An RGB colour, each channel in [0, 255].
using Rgb = std::array<int, 3>;

//! A planar polygon with holes, given twice: in 2D (any congruent or
//! affinely related flat copy; used only to triangulate it, in the browser)
//! and in 3D (where it is drawn). loops[0] is the outer loop, the others
//! holes; loop l has loops2d[l].size() == loops3d[l].size() corners.
struct ViewPolygon {
  std::vector<std::vector<Eigen::Vector2d>> loops2d;
  std::vector<std::vector<Vec3>> loops3d;
};

//! A hexahedral mesh drawn cell by cell: the faces of the shown cells that
//! no other shown cell covers (the boundary, and inside faces once a cut or
//! a filter hides cells), each in its cell's colour. A click gives the
//! cell's number and value. Cells use VTK's corner order (cell type 12).
struct ViewHexCells {
  std::vector<Vec3> points;
  std::vector<std::array<int, 8>> cells;
  std::vector<Rgb> colors;       // per cell
  std::vector<double> values;    // per cell (e.g. the scaled Jacobian), shown on click and filtered on
  std::string value_label = "value";
  //! Per cell and face (kViewHexFaces order), the cell across the face or -1.
  std::vector<std::array<int, 6>> neighbors;
};

//! The six faces of a hexahedron (VTK corner order) as local corner indices,
//! counter-clockwise seen from outside; the hex module's kHexFaces order.
inline constexpr std::array<std::array<int, 4>, 6> kViewHexFaces{{
    {0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};

//! Per cell and face, the other cell sharing that face (the same four
//! corners), or -1 on the boundary.
std::vector<std::array<int, 6>> hex_face_neighbors(const std::vector<std::array<int, 8>>& cells);

//! How an object is drawn.
enum class ViewStyle {
  Solid,  // opaque, flat shaded, pickable
  Ghost,  // translucent grey context (e.g. the input model), not pickable, shown by a check box
};

//! One thing in the view.
struct ViewObject {
  std::string name;                     // "block 3"; shown as the title of its info box
  Rgb color{200, 200, 200};             // base colour (lit and shaded in the browser)
  ViewStyle style = ViewStyle::Solid;
  Mesh mesh;                            // triangles (model units), or empty when `polygons` is used
  std::vector<ViewPolygon> polygons;    // planar polygons, triangulated in the browser
  ViewHexCells hex;                     // or hexahedral cells (when hex.cells is not empty)
  Vec3 explode_offset = Vec3::Zero();   // displacement at the explode slider's full value (model units)
  std::vector<std::pair<std::string, std::string>> info;  // lines shown on click: (label, value)
};

//! A legend entry: a colour and what it means.
struct ViewLegendEntry {
  std::string label;
  Rgb color{};
};

//! Everything view.html shows.
struct ViewScene {
  std::string title;                    // page title and heading
  std::string subtitle;                 // one line under the heading
  std::vector<ViewLegendEntry> legend;  // colour key
  std::string ghost_label = "input model";  // label of the check box showing Ghost objects
  Vec3 towards_eye = Vec3(0.553, 0.408, 0.727);  // initial view: direction from the scene to the eye (y is up)
  std::vector<ViewObject> objects;
};

//! Colour of a milling direction / insertion axis, by the axis name of
//! decomposition.json ("+x", "-x", "+y", "-y", "+z", "-z"; grey for
//! anything else). Each is a pure hue (two equal channels): red, cyan,
//! green, magenta, blue, yellow, so the hue survives shading and blending
//! with grey (the browser tests rely on this).
Rgb direction_color(const std::string& axis);

//! "#rrggbb".
std::string to_hex(const Rgb& color);

}  // namespace subfab
