// SPDX-License-Identifier: GPL-3.0-or-later
//! \file finalize_blocks.h
//! The last step before export: turns the carved (and merged) blocks, held
//! in the canonical frame, into double meshes in the INPUT frame that are
//! valid on their own, whatever rounding did to them (thesis Section 4.2:
//! every block a closed height-field solid; the export of Chapter 4).
//!
//! Carving is exact, but the blocks are rounded to doubles, and rotating
//! them back to the input frame rounds once more. Near-coincident exact
//! points are common by construction (box planes stop one ulp from the mesh
//! at "first contact"), so rounding leaves zero-length edges, needles and
//! caps (a vertex on, or across, its opposite edge) whose normals are
//! garbage, and tiny self-intersections. This stage:
//!   1. maps every vertex back to the input frame with ONE rounding: input
//!      vertices get the input's own coordinates back; any other vertex c
//!      becomes rotation^T c computed as in twice the precision, rounded once;
//!   2. cleans the rounding artefacts deterministically, changing geometry by
//!      at most the tolerance: edges shorter than it are collapsed (keeping
//!      the endpoint lower along the milling direction, so base faces stay on
//!      the base), caps whose height is below it are removed by flipping
//!      their longest edge; repeated until nothing changes;
//!   3. verifies each block with exact predicates: closed, manifold, oriented,
//!      no zero-area face, no self-intersection, positive volume, and every
//!      face off the base faces the milling direction (cosine >= -1e-3, the
//!      `subfab validate` rule). A block that fails is an AlgorithmError
//!      naming it and what is wrong (nothing invalid is written).
//!
//! Blocks reduced to nothing by the cleanup (a wafer thinner than the
//! tolerance) are dropped and counted.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "subfab/core/progress.h"
#include "subfab/geometry/axis.h"
#include "subfab/decompose/decompose.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of finalize_blocks() and clean_rounded_block().
struct FinalizeOptions {
  double relative_tolerance = 1e-10;  // cleanup tolerance (unitless): edges shorter than, and caps lower than,
                                      // this x scale are removed; scale = max(input bbox diagonal, largest
                                      // |coordinate|) in model units (rounding errors grow with |coordinate|)
  double normal_tolerance = 1e-3;     // verification: off-base faces need unit n.d >= -this (unitless)
  int max_passes = 32;                // cleanup passes (collapse all short edges, flip all caps) per block
  Progress* progress = nullptr;       // progress and info (nullptr: silent)
};

//! One finished block.
struct FinalBlock {
  Mesh mesh;                       // closed, outward-oriented, input coordinates (model units)
  Axis axis = Axis::PosZ;          // milling axis in the canonical frame
  Vec3 direction = Vec3::UnitZ();  // unit milling direction in input coordinates (rotation^T x axis)
  int source_box = -1;             // the ordered box it was carved from
  Mesh frame_mesh;                 // the block as decompose() holds it (canonical frame): mesh's faces and
                                   // vertex ids, each vertex the canonical point it was rounded from
                                   // (frame_twin()); `subfab validate` measures check 10 on it
};

//! What the cleanup did.
struct CleanupReport {
  std::size_t num_collapsed_edges = 0;  // short edges collapsed
  std::size_t num_flipped_edges = 0;    // cap edges flipped
};

//! Result of finalize_blocks().
struct FinalizeResult {
  std::vector<FinalBlock> blocks;       // in the order of the input blocks (minus dropped ones)
  CleanupReport cleanup;                // summed over blocks
  std::size_t num_dropped_blocks = 0;   // blocks thinner than the tolerance, removed entirely
};

//! The canonical-frame twin of a block rounded to the input frame: vertex i
//! of `rounded` was rounded from frame[i] (canonical frame), and cleanups
//! (finalize_blocks()'s collapses and flips, the export's single-precision
//! cleanup) made `finished` of it. Returns `finished`'s faces (same vertex
//! ids) with each vertex replaced by the frame point that was rounded to it
//! (a collapse keeps one of the rounded points; the least frame point, in
//! lexicographic order, when several rounded to it), or, for a point no
//! frame point rounded to (moved by a cleanup), by `rotation` x it
//! (canonical = rotation x input, rounded once). So the twin rounds back to
//! `finished` vertex by vertex, and shares its points with the canonical
//! input and the neighbouring blocks wherever `finished` does.
Mesh frame_twin(const Mesh& finished, const Mesh& rounded, const std::vector<Vec3>& frame,
                const Eigen::Matrix3d& rotation);

//! Maps the blocks of `result` (canonical frame) to the input frame, cleans
//! the rounding artefacts and verifies every block (see the file comment).
//! Deterministic and independent of the thread count (blocks are finished
//! in parallel, each on its own).
//! \param input  the mesh given to decompose() (input frame)
//! \param result decompose()'s result (rotation, canonical mesh, blocks)
//! \throw AlgorithmError naming the block when one cannot be made valid.
FinalizeResult finalize_blocks(const Mesh& input, const DecomposeResult& result, const FinalizeOptions& options = {});

//! Steps 1-3 of finalize_blocks() without the throw: per block of `result`,
//! what finalize_blocks() would report wrong with it after rounding to the
//! input frame and cleanup (block_defect(); empty: it would be valid, or
//! dropped as thinner than the tolerance). decompose_smoothed() checks its
//! carve rounds with it (a block made of a restored surface can cross
//! itself once rounded). Same parameters as finalize_blocks().
std::vector<std::string> block_defects_after_rounding(const Mesh& input, const DecomposeResult& result,
                                                      const FinalizeOptions& options = {});

//! Steps 1-3 of finalize_blocks() on one block at a time, for a stage that
//! makes new blocks after the carve (merge_within_tolerance(): a merged
//! milled shape can be valid in the canonical frame and not once rounded to
//! the input frame: anchor.off at --tolerance 5e-4, a non-manifold block
//! 012). Holds references to `input` and `result.canonical`: they must
//! outlive it (result.blocks may change meanwhile). Thread-safe.
class RoundedBlockCheck {
 public:
  RoundedBlockCheck(const Mesh& input, const DecomposeResult& result, const FinalizeOptions& options = {});
  ~RoundedBlockCheck();
  RoundedBlockCheck(const RoundedBlockCheck&) = delete;
  RoundedBlockCheck& operator=(const RoundedBlockCheck&) = delete;
  //! What finalize_blocks() would report wrong with `block` (canonical
  //! frame); empty when it would be valid, or dropped as thinner than the
  //! cleanup tolerance. `finished`, when given, receives the block as
  //! finalize_blocks() would make it (input frame; empty when dropped).
  std::string defect(const Block& block, Mesh* finished = nullptr) const;
  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

//! The cleanup of step 2 on one block: collapses edges shorter than
//! `tolerance` (model units) and flips the longest edge of caps lower than
//! it, until nothing changes. Vertices are kept in their order (unused ones
//! removed); the mesh may end up empty when the block is thinner than the
//! tolerance. \param direction unit milling direction (a collapse keeps the
//! endpoint with the smaller v.direction).
//! \throw InvalidMeshError when `block` is not an oriented 2-manifold.
CleanupReport clean_rounded_block(Mesh& block, const Vec3& direction, double tolerance,
                                  const FinalizeOptions& options = {});

//! clean_rounded_block() at the export's own tolerance (relative_tolerance
//! x rounding_scale(block)) for a block whose rounding to doubles left
//! zero-area or flipped faces (the merges within a tolerance, the sliver
//! stage's thickening). Returns that tolerance (how far a vertex may have
//! moved, model units) when the block is then a non-empty closed solid
//! without zero-area faces; nullopt otherwise (or when the cleanup throws).
std::optional<double> clean_to_closed_solid(Mesh& block, const Vec3& direction);

//! The verification of step 3 on one block: an empty string when `block` is
//! closed, manifold, oriented, free of zero-area faces (exact) and of
//! self-intersections (exact predicates), has positive volume and is a
//! height field along `direction` with validate's tolerances (normal
//! `options.normal_tolerance`, base plane 1e-9 x max(1, `diagonal`));
//! otherwise what is wrong, in words.
std::string block_defect(const Mesh& block, const Vec3& direction, double diagonal,
                         const FinalizeOptions& options = {});

}  // namespace subfab
