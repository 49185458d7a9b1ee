// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_unfolding_view.h
//! OUTDIR/view.html of an unfoldable simplification (thesis Chapter 3's
//! result): the simplified model with its facets coloured by net, the nets
//! laid flat beside it as they are cut from the sheet (same colours), the
//! input as a translucent ghost, an explode slider moving each facet out
//! along its normal, and a click on a facet giving its number, net, area and
//! normal. Read from OUTDIR/unfold.json (facets' 3D and sheet corners).
#pragma once

#include <filesystem>

#include "subfab/view/view_scene.h"
#include "subfab/view/write_view_html.h"

namespace subfab {

//! Options of write_unfolding_view().
struct UnfoldingViewOptions {
  const Mesh* input = nullptr;  // the input model, drawn as a ghost when given
  WriteViewOptions html;        // where three.js is
};

//! The scene of an unfolding folder (what view.html shows).
//! \throw IoError when OUTDIR/unfold.json is missing or malformed.
ViewScene unfolding_scene(const std::filesystem::path& outdir, const Mesh* input);

//! Writes OUTDIR/view.html for the unfolding in `outdir`.
//! \throw IoError when unfold.json cannot be read, three.js is missing or the page cannot be written.
void write_unfolding_view(const std::filesystem::path& outdir, const UnfoldingViewOptions& options = {});

}  // namespace subfab
