// SPDX-License-Identifier: GPL-3.0-or-later
//! \file match_frame_blocks.h
//! Checks 3, 4 and 10 in decompose's working frame (issue 17; docs/validate.md):
//! the distances of check 10 and the volumes of checks 3 and 4 (below the
//! file comment's argument, outside_volume_bound() and overlap_volume_bound()).
//!
//! decompose() works in a frame turned from the input's (thesis 4.3.1:
//! canonical = R x input, rotate_into_frame()), where neighbouring blocks
//! and the turned input share their faces exactly. The exported blocks are
//! rounded back to the input frame: there they share no face exactly, CGAL's
//! unions of neighbours fail and the exact overlay of near-coplanar faces
//! takes seconds to minutes per box (egea, fertility at --tolerance). So
//! within a tolerance decompose also writes each block as it holds it in the
//! frame (OUTDIR/frame/block_NNN.obj, frame_twin(): the same faces, each
//! vertex the frame point that was rounded to it), and validate measures the
//! deviation there, on the input turned exactly as decompose turned it.
//!
//! Why the frame measure bounds the deviation of the exported blocks: let
//! S_f = rotate_into_frame(S, R) and B_f the frame blocks. Every vertex of S
//! and of an exported block E lies within delta of R^T times its twin in
//! S_f or B_f (delta measured here, vertex by vertex, faces identical), so
//! every point of the surfaces (a convex combination of its face's corners)
//! lies within delta of R^T times its twin, and R^T stretches distances by
//! at most `stretch` (R is a rotation up to rounding). A point of the model
//! made, ∂(S ∪ E...), is then within delta of R^T x a point of ∂(S_f ∪ B_f
//! ...) (gaps of at most 2 delta that rounding opens between blocks sharing
//! a face in the frame are one face rounded twice, not surface of the model
//! made: glued blocks), which lies within the frame deviation D of a point
//! of ∂S_f, itself within delta of ∂S: the deviation is at most stretch x D
//! + 2 delta (+ the rounding of computing delta), rounding() below.
//!
//! The frame blocks cannot lie: every face must be the exported block's
//! face (same vertex ids) and every vertex must turn back to within
//! max_vertex_offset of the exported vertex, else the block is refused; and
//! the offsets found (rounding, snapping: ~1e-16 to 1e-9 of the diagonal)
//! are added to the bound whatever they are.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of match_frame_blocks().
struct FrameMatchOptions {
  double snap_tolerance = 1e-9;      // rotate_into_frame()'s (decomposition.json "frame"."snap_tolerance")
  double max_vertex_offset = 1e-6;   // a frame vertex turned back may lie at most this x max(bbox diagonal,
                                     // largest |coordinate|) from its exported vertex (rounding and the
                                     // snapping of rotate_into_frame() move vertices by ~1e-16 to 1e-9 of it)
  double max_orthogonality_error = 1e-9;  // max |(R^T R - I)_ij|: beyond it R is not a rotation (refused)
};

//! Result of match_frame_blocks().
struct FrameMatch {
  Mesh input;                      // the input in the frame: rotate_into_frame(input, R, snap_tolerance)
  double input_offset = 0.0;       // max |input vertex - R^T x its frame vertex| (model units)
  double block_offset = 0.0;       // max over the matched blocks' vertices, the same (model units)
  double stretch = 1.0;            // >= 1: |R^T x| <= stretch |x|
  double computing_error = 0.0;    // bound of the rounding of the offsets' computation (model units)
  std::string frame_error;         // non-empty when R is not a rotation: no block is matched
  std::vector<std::string> refused;  // per block: why its frame block is refused (empty: it matches)
  std::size_t num_refused() const;
  //! What the frame measure's bound gains when moved back to the exported
  //! blocks: a deviation D measured in the frame is at most stretch x D +
  //! rounding() in the input frame (see the file comment).
  double rounding() const { return 2.0 * std::max(input_offset, block_offset) + computing_error; }
};

//! Turns `input` into the frame `rotation` as decompose() does and checks
//! each frame block against its exported block (see the file comment).
//! blocks[i] and frame_blocks[i] are the exported block (input frame) and
//! the frame block of block i. Deterministic, parallel over the blocks.
FrameMatch match_frame_blocks(const Mesh& input, const std::vector<const Mesh*>& blocks,
                              const std::vector<const Mesh*>& frame_blocks, const Eigen::Matrix3d& rotation,
                              const FrameMatchOptions& options = {});

//! Check 4 in decompose's frame: a bound on vol(E \\ S), the volume of the
//! exported block E outside the input S, from vol(F \\ S_f), measured
//! exactly on its frame block F against the input in the frame S_f (they
//! share their faces there, so the exact difference is cheaper: fertility
//! at 1e-3, 1.8 times). With E' = R^T F and S' = R^T S_f (the exact images),
//! E \\ S lies in (E' \\ S') ∪ (E △ E') ∪ (E ∩ (S' \\ S)), and
//! vol(E' \\ S') = |det R^T| vol(F \\ S_f) <= stretch^3 vol(F \\ S_f). E and
//! E' have the same faces, each vertex within delta = max(input_offset,
//! block_offset) + computing_error: a point of E △ E' has different winding
//! numbers in the two, so the moving surface (every vertex moved linearly)
//! passes through it, and each moving face stays within delta of its face
//! in E: E △ E' lies in the union of the faces of E grown by delta, of volume
//! at most 2 delta A + pi/2 delta^2 P + 4/3 pi delta^3 per face (Steiner's
//! formula for a triangle of area A and perimeter P). Likewise S' \\ S for
//! the faces of S that come within delta of E's bounding box. delta also
//! takes the rounding of the difference's vertices to doubles (half an ulp
//! of the largest coordinate), which moves the measured volume by at most
//! the same sums.
//! \param frame_volume vol(F \\ S_f), outside_part() on match.input
//! \param block        E, the exported block (its frame block matched: match.refused empty for it)
//! \param input        S, the input as given to match_frame_blocks()
//! \return >= vol(E \\ S) (model units^3)
double outside_volume_bound(double frame_volume, const Mesh& block, const Mesh& input, const FrameMatch& match);

//! Check 3 in decompose's frame: a bound on vol(A ∩ B) of two exported
//! blocks from vol(F_A ∩ F_B) of their frame blocks, as
//! outside_volume_bound(): A ∩ B lies in (A' ∩ B') ∪ (A △ A') ∪ (B △ B'),
//! the first of volume <= stretch^3 vol(F_A ∩ F_B), the others held by the
//! faces of A near B's box, and of B near A's, grown by delta.
//! \param frame_volume vol(F_A ∩ F_B), blocks_overlap() of the frame blocks
//! \return >= vol(A ∩ B) (model units^3)
double overlap_volume_bound(double frame_volume, const Mesh& a, const Mesh& b, const FrameMatch& match);

}  // namespace subfab
