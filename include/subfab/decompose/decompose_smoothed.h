// SPDX-License-Identifier: GPL-3.0-or-later
//! \file decompose_smoothed.h
//! Thesis Section 4.3.5 ("Faithfulness vs Complexity"), both steps as one
//! automatic path (`subfab decompose --smooth`): fewer blocks for a detailed
//! model by decomposing a low-pass filtered version of it, then putting the
//! details back into the blocks.
//!
//!   1. smooth_for_decomposition(input)           Taubin low-pass, Hausdorff cap
//!   2. decompose(smoothed)                       the exact pipeline, its boxes kept
//!   3. restore_details(original, smoothed, boxes) Laplacian reconstruction under
//!                                                 the boxes and directions; each box
//!      (shrunk to the smoothed surface) may first grow by the smoothing's largest
//!      vertex move on every side but its base, where the added slab meets no later
//!      box in carve order (no later block loses material): the room of its region
//!   4. carve_blocks(restored, grown boxes)       the same boxes, same order; every
//!      block checked to be a height field along its axis (is_height_field, the
//!      rule of carve_blocks and validate) and valid once rounded to the input
//!      frame (block_defects_after_rounding(): the export's finalize_blocks()
//!      check, self-intersections included), and the surface of the restored solid checked
//!      to lie on the blocks; where a block fails or a face is not covered, the
//!      vertices there are held at their smoothed positions and 3.-4. run
//!      again (at most max_carve_rounds times; when no vertex is left to hold,
//!      once more with the boxes not grown)
//!   5. merge_blocks()                             the 4.3.4 post-processing
//!   6. the deviation of the blocks' union (the restored solid, carved exactly)
//!      from the ORIGINAL input: symmetric Hausdorff distance (CGAL, bounded
//!      error) and area-weighted mean distance over the whole surface.
//!
//! With a tolerance T (DecomposeOptions::tolerance_fraction / tolerance_abs,
//! of the INPUT's diagonal; `decompose --smooth=F --tolerance T`), steps 3-6
//! are replaced: the smoothed model is decomposed within T (the allowances of
//! decompose(), issue 17: exact height-field blocks, undercuts within T
//! filled), and nothing is restored. The deviations add up (triangle
//! inequality): the blocks' union lies within the smoothing's largest vertex
//! move (<= F, a bound of its Hausdorff distance) plus decompose()'s measured
//! deviation bound (<= T) of the input, reported as max_deviation (a bound).
//! Slivers are judged at T, as within T alone. The blocks decompose the
//! smoothed model (written as OUTDIR/input_smoothed.obj) within T.
//!
//! The blocks decompose the RESTORED solid (result.decomposition.repaired_input,
//! input coordinates): `subfab validate` checks them against it (written as
//! OUTDIR/input_restored.obj).
#pragma once

#include <cstddef>

#include "subfab/decompose/decompose.h"
#include "subfab/fidelity/restore_details.h"
#include "subfab/fidelity/smooth_for_decomposition.h"

namespace subfab {

//! Options of decompose_smoothed().
struct SmoothedDecomposeOptions {
  DecomposeOptions decompose;       // the decomposition of the smoothed model (its progress is used throughout);
                                    // max_overhang_deg must be 0; a tolerance (of the input's diagonal) gives
                                    // the path without restoration (file comment); the height limit is of the
                                    // input's diagonal too
  SmoothOptions smooth;             // the smoothing (max_deviation: the cap, `--smooth F`)
  RestoreDetailsOptions restore;    // the restoration (its `held` is set here)
  int max_carve_rounds = 4;         // restorations, each carved and checked (>= 1); the last holds every
                                    // vertex near a failing block at its smoothed position
  double hausdorff_error = 1e-5;    // error bound of the measured deviation, fraction of the diagonal (> 0)
};

//! What decompose_smoothed() measured.
struct SmoothedDecomposeReport {
  SmoothReport smooth;              // step 1 (deviation of the smoothed model from the input)
  RestoreDetailsReport restore;     // step 3, last round
  std::size_t num_blocks_smoothed = 0;  // blocks of the smoothed model's decomposition
  std::size_t num_blocks = 0;           // blocks made from the restored solid
  int num_carve_rounds = 0;             // restorations carved (1: the first one held)
  std::size_t num_failed_blocks = 0;    // blocks that failed the checks, summed over rounds
  std::size_t num_rounding_failures = 0;  // of which failed only once rounded to the input frame (finalize_blocks())
  std::size_t num_uncovered_faces = 0;  // restored faces not on the blocks, summed over rounds
  std::size_t num_held = 0;             // vertices held at their smoothed positions after failed carves
  double bbox_diagonal = 0;         // of the input, model units
  double max_deviation = 0;         // symmetric Hausdorff distance, blocks' union <-> input surfaces, model units
                                    // (within a tolerance: its bound, decomposed_deviation + the measured bound)
  double mean_deviation = 0;        // area-weighted mean distance of the blocks' union's surface to the input,
                                    // over the whole surface, model units (within a tolerance: the smoothed
                                    // model's; the material filled under undercuts is not in it)
  double deviation_error = 0;       // absolute error bound of max_deviation, model units
  double smoothed_mean_deviation = 0;  // the same mean for the smoothed model (before restoration)
  bool within_tolerance = false;    // decomposed within `tolerance` and not restored (the file comment)
  double tolerance = 0;             // within a tolerance: T, model units
  double decomposed_deviation = 0;  // within a tolerance: bound of the decomposed (smoothed) model's Hausdorff
                                    // distance from the input (the smoothing's largest vertex move), model units
  double restore_seconds = 0;       // steps 3-6
  double fraction(double x) const { return bbox_diagonal > 0 ? x / bbox_diagonal : 0; }
};

//! Result of decompose_smoothed().
struct SmoothedDecomposeResult {
  DecomposeResult decomposition;  // the final blocks (canonical frame); repaired_input: the restored solid in
                                  // input coordinates (what the blocks decompose), canonical: the same in the
                                  // canonical frame; statistics of the smoothed model's decomposition
  Mesh smoothed;                  // the smoothed model (input coordinates)
  SmoothedDecomposeReport report;
};

//! Smooths, decomposes, restores the details and carves the blocks again
//! (see the file comment; thesis Section 4.3.5).
//! \param input closed, manifold, outward-oriented, self-intersection-free solid
//! \throw InvalidMeshError when `input` is not such a solid; InvalidArgumentError
//!        on bad options; AlgorithmError when the smoothed model still has
//!        features no height-field block can cover (smooth more) or a stage fails.
SmoothedDecomposeResult decompose_smoothed(const Mesh& input, const SmoothedDecomposeOptions& options);

}  // namespace subfab
