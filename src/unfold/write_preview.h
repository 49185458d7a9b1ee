// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_preview.h
//! Private: preview.png of the unfolding export (stage 7, after thesis
//! Chapter 3): the simplified model on the left (flat shaded, facets coloured
//! by normal, facet borders dark), the sheets with the nets on the right.
#pragma once

#include <filesystem>
#include <vector>

#include "subfab/mesh/mesh.h"
#include "subfab/unfold/export_unfolding.h"
#include "subfab/unfold/poly_mesh.h"
#include "subfab/unfold/unfold_nets.h"
#include "unfold/write_nets.h"

namespace subfab::unfold_detail {

//! Draws and writes the preview (options.preview_width x preview_height
//! pixels, at least 64 x 64). `tri`, `tri_facet`: the facets' triangulation.
//! \throw IoError when the file cannot be written.
void write_preview(const PolyMesh& mesh, const Mesh& tri, const std::vector<int>& tri_facet, const Drawing& drawing,
                   const SheetLayout& layout, const Unfolding& unfolding, const ExportUnfoldingOptions& options,
                   const std::filesystem::path& path);

}  // namespace subfab::unfold_detail
