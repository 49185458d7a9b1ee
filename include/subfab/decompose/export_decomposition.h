// SPDX-License-Identifier: GPL-3.0-or-later
//! \file export_decomposition.h
//! Writes a decomposition in the form `subfab validate` and CAM software read:
//!   OUTDIR/decomposition.json   the description (format below)
//!   OUTDIR/blocks/block_NNN.obj each block, input coordinates and units
//!   OUTDIR/mill/block_NNN.stl   the block moved rigidly so its milling
//!                               direction is +Z and its base lies on z = 0
//!   OUTDIR/frame/block_NNN.obj  (within a tolerance only) the block as
//!                               decompose holds it, in its working frame
//!                               (canonical = rotation x input), every
//!                               coordinate exact (frame_twin(): same faces
//!                               and vertex ids as blocks/block_NNN.obj,
//!                               each vertex the point that was rounded to
//!                               it); `subfab validate` measures check 10 on
//!                               them (docs/validate.md)
//!
//! decomposition.json:
//!   {"format": "subfab.decomposition", "version": 1,
//!    "input": {"path", "vertices", "faces", "bbox_diagonal",
//!              "repair": null, or after a repair of infeasible features (4.3.5) {"mesh": "input_repaired.obj"
//!              (OUTDIR-relative, input coordinates), "vertices", "faces", "num_features", "num_creases",
//!              "num_vertices", "num_rounds", "num_faces_removed", "num_faces_new", "max_deviation",
//!              "mean_deviation" (model units), "max_deviation_fraction", "mean_deviation_fraction" (x bbox
//!              diagonal), "hausdorff_error" (model units), "max_deviation_cap_fraction", "precision_snap":
//!              null, or when the frame is feasible only with the input's coordinates snapped within the
//!              file's own rounding (then num_features = 0 and the deviations are the largest and mean vertex
//!              move) {"coordinate_rounding" (model units), "snap_tolerance" (x turned bbox diagonal),
//!              "num_vertices_moved"}},
//!              "mesh_repair": null, or after `decompose --repair` changed the input the record of
//!              mesh_repair_to_json() plus "mesh": "input_mesh_repaired.obj" (OUTDIR-relative): the solid
//!              made of the input file, which "vertices", "faces" and "repair" then describe,
//!              "smoothing": null, or after `decompose --smooth` (decompose_smoothed(), thesis 4.3.5) {"mesh":
//!              "input_restored.obj" (the restored solid the blocks decompose), "smoothed_mesh":
//!              "input_smoothed.obj", "cap_fraction", "passes" (Taubin passes applied, --smooth-passes), "lambda", "mu",
//!              "num_blocks_smoothed", "num_blocks", "max_deviation",
//!              "mean_deviation" (blocks' union vs the input, model units), "max_deviation_fraction",
//!              "mean_deviation_fraction", "hausdorff_error", the smoothed model's deviations and the
//!              restoration's counts},
//!              "decomposed_mesh": the mesh the blocks decompose (the input path, "input_mesh_repaired.obj",
//!              "input_repaired.obj" or "input_restored.obj")},
//!    "rotation": 3x3 (canonical = rotation x input),
//!    "frame": (within a tolerance only) {"snap_tolerance" (rotate_into_frame()'s, x bbox diagonal),
//!              "max_rounding" (model units: largest distance between a vertex of blocks/ and its frame/
//!              twin turned back, informational; validate measures it again)},
//!    "parameters": {"max_height_fraction", "max_height", "machine", "orient", "grid_factor"},
//!    "blocks": [{"id", "mesh", "machine_mesh", ["frame_mesh" (within a tolerance only)],
//!                "direction" (unit, input coordinates),
//!                "axis" (canonical, "+z"), "base_offset" (min of v.direction), "height",
//!                "volume", "thickness" (block_thickness(): smallest mean chord length along the
//!                block's frame axes, model units), "bbox" {"min", "max"}, "machine_transform" 4x4
//!                (input -> machine)}],
//!    "summary": {"num_blocks", "material_volume_fraction", "min_block_volume_fraction",
//!                "min_thickness" (model units), "min_thickness_fraction" (x bbox diagonal)},
//!    "timings_s": {"orient", "field", "grow", "cover", "resolve", "carve", "total"}}
//! Unlimited parameters are written as null. Everything but "timings_s" is
//! byte-identical for identical input and options, whatever the thread count.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "subfab/decompose/decompose.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! File name (in OUTDIR) of the repaired input, named by "input"."repair"."mesh".
inline constexpr const char* kRepairedInputFile = "input_repaired.obj";
//! File names (in OUTDIR) of `decompose --smooth`'s restored solid (what the blocks decompose, named by
//! "input"."smoothing"."mesh") and of the smoothed model it was decomposed as.
inline constexpr const char* kRestoredInputFile = "input_restored.obj";
inline constexpr const char* kSmoothedInputFile = "input_smoothed.obj";

//! One block as exported (input coordinates).
struct ExportedBlock {
  Mesh mesh;                // input coordinates
  Mesh machine_mesh;        // machine coordinates (direction +Z, base on z = 0, min x = min y = 0)
  Vec3 direction;           // unit milling direction, input coordinates
  Axis axis;                // canonical axis
  double base_offset = 0;   // min of v.direction over the block (model units)
  double height = 0;        // max - min of v.direction (model units)
  double volume = 0;        // model units^3
  double thickness = 0;     // block_thickness() in its machine frame (model units)
  double max_overhang_deg = 0;  // steepest face off the base leaning past vertical (degrees; 0 when none;
                                // hundredths of a degree from rounding on exact blocks; <= --max-overhang)
  BoundingBox bbox;         // input coordinates
  Eigen::Matrix4d machine_transform = Eigen::Matrix4d::Identity();  // input -> machine coordinates
  Mesh frame_mesh;          // canonical frame, exact: what `mesh` was rounded from (frame_twin(); same faces)
  double frame_rounding = 0;  // max |mesh vertex - rotation^T x frame vertex| (model units)
  bool single_precision_ok = true;  // its STL (float32) is a closed solid without self-intersections
                                    // (false: the cleanup could not make it one; validate check 8 fails)
};

//! The rigid map of canonical axis `axis` to +Z (a signed permutation with
//! determinant +1): machine = axis_to_machine(axis) x canonical + shift.
Eigen::Matrix3d axis_to_machine(Axis axis);

//! A finished block (input frame) in machine coordinates: moved by
//! axis_to_machine(axis) x rotation (an exact signed permutation of the
//! rotation's rows, each coordinate rounded once), then shifted so that its
//! bounding box starts at the origin (`shift`, when given, receives it).
//! Same vertex ids as `block`.
Mesh machine_mesh_of(const Mesh& block, Axis axis, const Eigen::Matrix3d& rotation, Vec3* shift = nullptr);

//! Builds the exported blocks from a decomposition: finalize_blocks() maps
//! them to the input frame (one rounding), cleans the rounding artefacts and
//! verifies each block; machine meshes are the final blocks moved by
//! axis_to_machine(axis) x rotation (each coordinate rounded once), then
//! shifted so the block's minimum corner is at the origin.
//! 	hrow AlgorithmError when a block cannot be made valid (see finalize_blocks()).
std::vector<ExportedBlock> make_exported_blocks(const Mesh& input, const DecomposeResult& result,
                                                Progress* progress = nullptr);

//! What export_decomposition() writes besides the blocks.
struct ExportInfo {
  std::string input_path;   // as given by the user
  DecomposeOptions options; // the options used (for "parameters")
  nlohmann::ordered_json mesh_repair = nullptr;  // "input"."mesh_repair": null, or the record of the
                                                 // repair (`decompose --repair`) with its "mesh"
  nlohmann::ordered_json smoothing = nullptr;    // "input"."smoothing": null, or the record of
                                                 // `decompose --smooth` (decompose_smoothed()) with its "mesh", the
                                                 // restored solid the blocks decompose (result.repaired_input)
};

//! The decomposition.json document (as text, 2-space indented, fields in the
//! order above).
std::string decomposition_json(const Mesh& input, const DecomposeResult& result,
                               const std::vector<ExportedBlock>& blocks, const ExportInfo& info);

//! Writes OUTDIR/decomposition.json, OUTDIR/blocks/*.obj and OUTDIR/mill/*.stl,
//! and within a tolerance (result.tolerance > 0) OUTDIR/frame/*.obj (creating
//! the folders; stale block files from an earlier run are removed; at
//! tolerance 0 the output is what it was before the frame blocks existed).
//! Progress and cleanup info go to info.options.progress.
//! \return the exported blocks (make_exported_blocks()), as written
//! \throw IoError when a file cannot be written; AlgorithmError when a block
//!        cannot be made valid (nothing is written or removed then).
std::vector<ExportedBlock> export_decomposition(const Mesh& input, const DecomposeResult& result,
                                                const ExportInfo& info, const std::filesystem::path& outdir);

}  // namespace subfab
