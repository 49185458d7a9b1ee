// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_assembly_sheet.h
//! OUTDIR/assembly.html: the cut list and the gluing instructions of a
//! decomposition, one self-contained printable page. Per block: its number,
//! stock size (mm when a scale is known, from mill.json, --size or --scale;
//! model units otherwise), milling direction, machining time (from
//! mill.json), a picture of the block and one of where it goes (the blocks
//! glued before it in grey, it in colour); the blocks in a gluing order in
//! which each slides into place along a free axis (plan_gluing_order()).
#pragma once

#include <filesystem>
#include <string>

#include "subfab/core/progress.h"
#include "subfab/view/plan_gluing_order.h"
#include "subfab/view/read_decomposition.h"
#include "subfab/view/read_mill_info.h"

namespace subfab {

//! Options of write_assembly_sheet().
struct AssemblySheetOptions {
  std::filesystem::path mill_dir;  // GCODE_DIR holding mill.json (subfab mill); empty = none
  double size_mm = 0;              // the model's largest dimension in mm (--size); 0 = not given
  double mm_per_unit = 0;          // the scale in mm per model unit (--scale); 0 = not given; wins over size_mm
  int picture_size = 200;          // pixels per side of each picture
  int resolution = 200;            // rays per side for the gluing order (GluingOptions::resolution)
  Progress* progress = nullptr;    // warnings (a scale that disagrees with mill.json's)
};

//! The sheet and what it says.
struct AssemblySheet {
  std::string html;          // the page
  GluingPlan plan;           // block positions in `plan` are indices into the folder's blocks
  double mm_per_unit = 0;    // the scale used (0: sizes in model units)
  double total_time_s = -1;  // sum of the known machining times; < 0 when none is known
};

//! The sheet of a decomposition folder, with mill.json's facts when `mill` is given.
AssemblySheet assembly_sheet(const DecompositionFolder& folder, const MillInfo* mill, const AssemblySheetOptions& options);

//! Reads OUTDIR (and mill.json when options.mill_dir is set) and writes OUTDIR/assembly.html.
//! \throw IoError when a file cannot be read or written;
//!        InvalidArgumentError for a non-positive size or scale.
AssemblySheet write_assembly_sheet(const std::filesystem::path& outdir, const AssemblySheetOptions& options = {});

}  // namespace subfab
