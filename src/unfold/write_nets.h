// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_nets.h
//! Private: the drawing of the nets laid out on sheets (cut lines, folds cut
//! from the top or from the back with their V-bit labels, facet ids) and its
//! nets.svg and nets.dxf writers (export stage 7; nets of thesis Section
//! 3.3.3, fabrication output left as future work in Section 3.4).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "subfab/mesh/mesh.h"
#include "subfab/unfold/export_unfolding.h"
#include "subfab/unfold/poly_mesh.h"
#include "subfab/unfold/unfold_nets.h"

namespace subfab::unfold_detail {

// One line of the drawing: a cut or a fold.
struct Segment {
  Vec2 a, b;
  int kind;  // 0 cut, 1 fold top, 2 fold back
  std::string label;
};

struct Label {
  Vec2 at;
  std::string text;
};

struct Drawing {
  std::vector<Segment> segments;
  std::vector<Label> facet_labels;
  double text_size = 1;
};

//! Interior point of each facet in the layout: centroid of the largest
//! triangle of the facet in `tri` (tri_facet[t]: facet of triangle t).
std::vector<Vec2> label_points(const PolyMesh& mesh, const SheetLayout& layout, const Mesh& tri,
                               const std::vector<int>& tri_facet);

//! The cut and fold lines of every facet edge in the layout (a fold once,
//! from its parent's side) and the facet labels at `label_at`.
Drawing make_drawing(const PolyMesh& mesh, const Unfolding& unfolding, const SheetLayout& layout,
                     const std::vector<Vec2>& label_at);

//! Writes the drawing with the sheet outlines as SVG (y up turned to y
//! down). \throw IoError when the file cannot be written.
void write_svg(const Drawing& d, const SheetLayout& layout, const std::filesystem::path& path);

//! Writes the drawing with the sheet outlines as DXF (layers CUT, FOLD_TOP,
//! FOLD_BACK, LABELS, SHEETS). \throw IoError when the file cannot be written.
void write_dxf(const Drawing& d, const SheetLayout& layout, const std::filesystem::path& path);

}  // namespace subfab::unfold_detail
