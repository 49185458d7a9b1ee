// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_decomposition_view.h
//! OUTDIR/view.html of a height-field decomposition (thesis Chapter 4's
//! result, shown the way the thesis's figures show it): the decomposed model
//! as a translucent ghost and its blocks coloured by milling direction, an
//! explode slider moving each block away from the model's centre, and a
//! click on a block giving its number, direction, stock size, height and
//! volume.
#pragma once

#include <filesystem>

#include "subfab/core/progress.h"
#include "subfab/view/read_decomposition.h"
#include "subfab/view/view_scene.h"
#include "subfab/view/write_view_html.h"

namespace subfab {

//! Options of write_decomposition_view().
struct DecompositionViewOptions {
  const Mesh* model = nullptr;  // the decomposed model if already in memory (else read, see read_decomposed_model)
  WriteViewOptions html;        // where three.js is
  Progress* progress = nullptr; // a warning when the model cannot be found (the view then shows the blocks only)
};

//! The scene of a decomposition folder (what view.html shows).
ViewScene decomposition_scene(const DecompositionFolder& folder, const Mesh* model);

//! Reads the decomposition in `outdir` and writes OUTDIR/view.html.
//! \throw IoError when the folder cannot be read, three.js is missing, or the
//!        page cannot be written.
void write_decomposition_view(const std::filesystem::path& outdir, const DecompositionViewOptions& options = {});

}  // namespace subfab
