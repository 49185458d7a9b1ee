// SPDX-License-Identifier: GPL-3.0-or-later
//! \file read_decomposition.h
//! Reads what `subfab decompose` wrote (OUTDIR/decomposition.json and
//! OUTDIR/blocks/block_NNN.obj, see src/decompose/export_decomposition.cpp)
//! back, for the view and the assembly sheet: they work from the folder, so
//! they need nothing of the decomposition machinery.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! One block of a decomposition folder.
struct DecompositionBlock {
  std::size_t id = 0;       // its number (block_NNN)
  std::string axis;         // milling direction in the decomposition frame: "+x", "-x", ..., "-z"
  Vec3 direction = Vec3::UnitZ();  // milling direction in the input frame (unit)
  double volume = 0;        // model units^3
  double height = 0;        // along the milling direction, model units
  double max_overhang_deg = 0;
  BoundingBox bbox;         // input frame
  Vec3 stock_size = Vec3::Zero();  // machine-frame bounding box (x, y, z = height), model units
  Mesh mesh;                // OUTDIR/blocks/block_NNN.obj, input frame
};

//! A decomposition folder.
struct DecompositionFolder {
  std::filesystem::path folder;
  std::string input_path;   // "input.path" of decomposition.json (as given to decompose)
  std::string decomposed_mesh;  // the model the blocks decompose when decompose wrote it into OUTDIR (repaired,
                                // smoothed or restored), OUTDIR-relative ("input.decomposed_mesh"); empty: the input
  const char* model_label = "input model";  // what the blocks decompose, for the view: "input model",
                                            // "repaired input", "smoothed input" or "restored input"
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // input frame -> decomposition frame
  double bbox_diagonal = 0; // of the input, model units
  std::vector<DecompositionBlock> blocks;
};

//! Reads OUTDIR/decomposition.json and every block's mesh.
//! \throw IoError when a file is missing or malformed (names the file and
//!        the key, and says to run `subfab decompose` again).
DecompositionFolder read_decomposition(const std::filesystem::path& outdir);

//! The model the blocks decompose: the one decompose wrote into OUTDIR when
//! it repaired, smoothed or restored the input (OUTDIR/input_*.obj), else the input, looked for at input.path as written, then
//! relative to OUTDIR and to its parent. nullopt when none can be read; then
//! `*note` (if given) says what was tried.
std::optional<Mesh> read_decomposed_model(const DecompositionFolder& folder, std::string* note = nullptr);

}  // namespace subfab
