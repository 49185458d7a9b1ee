// SPDX-License-Identifier: GPL-3.0-or-later
//! \file export_decomposition.h
//! Writes a decomposition in the form `subfab validate` and CAM software read:
//!   OUTDIR/decomposition.json   the description (format below)
//!   OUTDIR/blocks/block_NNN.obj each block, input coordinates and units
//!   OUTDIR/mill/block_NNN.stl   the block moved rigidly so its milling
//!                               direction is +Z and its base lies on z = 0
//!
//! decomposition.json:
//!   {"format": "subfab.decomposition", "version": 1,
//!    "input": {"path", "vertices", "faces", "bbox_diagonal"},
//!    "rotation": 3x3 (canonical = rotation x input),
//!    "parameters": {"max_height_fraction", "max_height", "machine", "orient", "grid_factor"},
//!    "blocks": [{"id", "mesh", "machine_mesh", "direction" (unit, input coordinates),
//!                "axis" (canonical, "+z"), "base_offset" (min of v.direction), "height",
//!                "volume", "bbox" {"min", "max"}, "machine_transform" 4x4 (input -> machine)}],
//!    "summary": {"num_blocks", "material_volume_fraction", "min_block_volume_fraction"},
//!    "timings_s": {"orient", "field", "grow", "cover", "resolve", "carve", "total"}}
//! Unlimited parameters are written as null. Everything but "timings_s" is
//! byte-identical for identical input and options, whatever the thread count.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "subfab/decompose/decompose.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! One block as exported (input coordinates).
struct ExportedBlock {
  Mesh mesh;                // input coordinates
  Mesh machine_mesh;        // machine coordinates (direction +Z, base on z = 0, min x = min y = 0)
  Vec3 direction;           // unit milling direction, input coordinates
  Axis axis;                // canonical axis
  double base_offset = 0;   // min of v.direction over the block (model units)
  double height = 0;        // max - min of v.direction (model units)
  double volume = 0;        // model units^3
  BoundingBox bbox;         // input coordinates
  Eigen::Matrix4d machine_transform = Eigen::Matrix4d::Identity();  // input -> machine coordinates
};

//! The rigid map of canonical axis `axis` to +Z (a signed permutation with
//! determinant +1): machine = axis_to_machine(axis) x canonical + shift.
Eigen::Matrix3d axis_to_machine(Axis axis);

//! Builds the exported blocks from a decomposition: block vertices that are
//! input vertices get the input's exact coordinates back; the others are
//! rotated back (rotation^T x canonical). Machine meshes are made from the
//! canonical coordinates (an exact permutation, then a shift).
std::vector<ExportedBlock> make_exported_blocks(const Mesh& input, const DecomposeResult& result);

//! What export_decomposition() writes besides the blocks.
struct ExportInfo {
  std::string input_path;   // as given by the user
  DecomposeOptions options; // the options used (for "parameters")
};

//! The decomposition.json document (as text, 2-space indented, fields in the
//! order above).
std::string decomposition_json(const Mesh& input, const DecomposeResult& result,
                               const std::vector<ExportedBlock>& blocks, const ExportInfo& info);

//! Writes OUTDIR/decomposition.json, OUTDIR/blocks/*.obj and OUTDIR/mill/*.stl
//! (creating the folders; stale block files from an earlier run are removed).
//! \throw IoError when a file cannot be written.
void export_decomposition(const Mesh& input, const DecomposeResult& result, const ExportInfo& info,
                          const std::filesystem::path& outdir);

}  // namespace subfab
