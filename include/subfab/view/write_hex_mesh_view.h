// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_hex_mesh_view.h
//! What `subfab hexmesh` shows (issue 15 point 4, issue 14's preview): its
//! hexahedral mesh with every cell coloured by its scaled Jacobian (thesis
//! Appendix D's quality measure, Table D.1), in OUTDIR/view.html (the cells'
//! outer faces, a cut along x, y or z and a quality filter to see inside,
//! a click giving the cell's number and scaled Jacobian, the input as a
//! ghost, the tubular structure beside it) and in OUTDIR/preview.png (the
//! boundary coloured by quality next to the tubular structure, drawn by the
//! view module's own rasteriser).
//!
//! The view module sits below hex (it depends on mesh and core only), so
//! the mesh comes as plain arrays: the hex module's HexMesh has the same
//! layout (positions, 8 corner indices per cell in VTK order).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "subfab/view/view_scene.h"
#include "subfab/view/write_view_html.h"

namespace subfab {

//! A hexahedral mesh as plain arrays (VTK corner order).
struct HexCellArrays {
  std::vector<Vec3> points;
  std::vector<std::array<int, 8>> cells;
};

//! What the hex mesh view and preview show.
struct HexMeshView {
  HexCellArrays mesh;                   // the final mesh
  std::vector<double> scaled_jacobian;  // per cell of `mesh`
  HexCellArrays structure;              // the tubular structure (may be empty)
  const Mesh* input = nullptr;          // the input surface, a ghost in view.html (optional)
  std::string input_name;               // shown under the title
};

//! The colour of a cell of scaled Jacobian `sj`: one per histogram bin of
//! hexmesh.json: magenta for <= 0 (inverted), then (0, .1], ..., (.9, 1]
//! from red through yellow and green to blue (pure hues 0 to 220 degrees).
Rgb quality_color(double sj);

//! The legend of quality_color(): 11 entries, inverted first.
std::vector<ViewLegendEntry> quality_legend();

//! The scene of view.html: the cells by quality, the tubular structure
//! beside them (grey), the input as a ghost.
//! \throw InvalidArgumentError when the arrays disagree in size.
ViewScene hex_mesh_scene(const HexMeshView& view);

//! Writes view.html (see write_view_html()).
void write_hex_mesh_view(const HexMeshView& view, const std::filesystem::path& path, const WriteViewOptions& options = {});

//! Options of write_hex_mesh_preview().
struct HexMeshPreviewOptions {
  int width = 800, height = 450;  // pixels
  Vec3 towards_eye = Vec3(0.553, 0.408, 0.727);  // from the model to the eye (y is up)
};

//! The preview picture as PNG bytes: the boundary faces of the mesh, each
//! in its cell's quality_color() (flat shaded, region borders outlined),
//! and the tubular structure's boundary in grey to its right.
std::vector<std::uint8_t> hex_mesh_preview_png(const HexMeshView& view, const HexMeshPreviewOptions& options = {});

//! Writes hex_mesh_preview_png() to `path`. \throw IoError when it cannot be written.
void write_hex_mesh_preview(const HexMeshView& view, const std::filesystem::path& path,
                            const HexMeshPreviewOptions& options = {});

}  // namespace subfab
