// SPDX-License-Identifier: GPL-3.0-or-later
//! \file export_unfolding.h
//! Stage 7 of the unfoldable simplification (fabrication output the thesis
//! leaves as future work, Section 3.4): writes the simplified mesh, its nets
//! laid out on sheets for a V-groove milling machine, a JSON description and
//! a preview picture.
//!
//! Conventions (also in the README):
//! - The sheet lies with the model's OUTSIDE facing up ("top"). A convex fold
//!   (dihedral angle < 180 deg) closes on the inside, so its groove is cut
//!   from the back of the sheet; a concave (reflex) fold closes on the
//!   outside, so its groove is cut from the top. The V-bit angle is
//!   |180 - dihedral| (180 - dihedral for convex folds, dihedral - 180 for
//!   reflex ones): the groove's opening angle that closes exactly when folded.
//! - Sheet k occupies x in [k (W + gap), k (W + gap) + W] of the layout plane;
//!   vertices2d in unfold.json, nets.svg and nets.dxf use these coordinates
//!   (model units). Nets are rotated to their smallest bounding box, then
//!   packed in rows (first fit by decreasing height).
//! - simplified.obj: one polygon per facet (outer loop, counter-clockwise
//!   seen from outside); a facet with holes is written as the triangles of
//!   its constrained triangulation (no new vertices).
#pragma once

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/unfold/poly_mesh.h"
#include "subfab/unfold/unfold_nets.h"

namespace subfab {

//! Facet counts and quality numbers written to unfold.json's summary.
struct UnfoldSummary {
  std::size_t facets_mc = 0;           // facets after marching cubes (charts)
  std::size_t facets_after_masks = 0;  // facets after the masks
  std::size_t facets_final = 0;        // facets after deletion
  std::size_t nets = 0;
  double hausdorff = 0;  // model units, between simplified mesh and input
};

//! Options of export_unfolding() and layout_sheets().
struct ExportUnfoldingOptions {
  double sheet_width = 0;    // model units; 0 = one sheet large enough for all nets
  double sheet_height = 0;   // model units; 0 = unbounded
  int preview_width = 1600;  // pixels of preview.png
  int preview_height = 800;  // pixels
  Progress* progress = nullptr;
  nlohmann::ordered_json input = nullptr;  // "input" of unfold.json (first key) when not null: the
                                           // command's record of its input (path, repair)
};

//! Nets placed on sheets.
struct SheetLayout {
  //! positions[f][l][i]: layout-plane position of corner i of loop l of facet f.
  std::vector<std::vector<std::vector<Vec2>>> positions;
  std::vector<int> net_sheet;  // sheet of each net
  int num_sheets = 0;
  double sheet_width = 0, sheet_height = 0, gap = 0;  // model units
  std::vector<int> oversized_nets;                    // nets larger than the sheet
};

//! Rotates each net to its smallest bounding box and packs the nets on sheets.
SheetLayout layout_sheets(const Unfolding& unfolding, const ExportUnfoldingOptions& options = {});

//! V-bit angle (degrees) and side ("top" or "back") of a fold with the given
//! interior dihedral angle (degrees), following the conventions above.
double vbit_angle_deg(double dihedral_deg);
const char* vbit_side(double dihedral_deg);

//! Writes OUTDIR/simplified.obj, nets.svg, nets.dxf, unfold.json and
//! preview.png (see the conventions above; the JSON layout is in the README).
//! Creates `outdir` if needed.
//! \throw IoError when a file cannot be written.
void export_unfolding(const PolyMesh& mesh, const Unfolding& unfolding, const UnfoldSummary& summary,
                      const std::filesystem::path& outdir, const ExportUnfoldingOptions& options = {});

}  // namespace subfab
