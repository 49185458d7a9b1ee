// SPDX-License-Identifier: GPL-3.0-or-later
//! \file remove_slivers.h
//! No slivers (issue 17, "No slivers"; thesis Section 4.3.4, whose snapping
//! and merging exist so that no block is too thin to mill or glue): the last
//! stage of decompose(), after the merges within the tolerance.
//!
//! A block is a SLIVER when it is thinner than `min_thickness` where the
//! model is thicker, decided exactly as validate's check 9 decides it
//! (find_slivers(): the block's thickness is its smallest mean chord length
//! along the axes of its frame, block_thickness(); the model's thickness
//! there is the mean length of the input segments holding the block's
//! segments on a grid of lines along that axis). decompose() sets
//! min_thickness = max(1e-4 x diagonal, min(T, H / 4)) (H the height limit), as validate does.
//!
//! The rule: within a tolerance T > 0, every sliver is removed when that is
//! measured within T, in this order:
//! 1. DROPPED when the input surface stays within T of the other blocks
//!    without it (cheap: one bounded-error distance; CGAL's bounded-error
//!    Hausdorff distance, measure + error bound <= T): the one-sided
//!    distance from the input surface within T of the sliver's box (the
//!    input faces meeting the box widened by T, clipped to it) to the
//!    surfaces of the blocks within 2T of its box, sticking-out milled
//!    shapes included (they cover what they fill; a nearest point farther
//!    away would be farther than T). An input point farther than T from the
//!    sliver's box was within T of another block before (its distance to the
//!    sliver exceeds T), so this bounds the whole change of the coverage.
//!    The faces the drop exposes need no measure: they lie inside the input
//!    (cut faces between blocks, which the deviation does not count; the
//!    model's interior may stay empty), and a dropped block that stuck out
//!    only takes material away. The dropped volume is left empty (a dent at
//!    most T deep). Drops in one pass are more than 2T apart; passes repeat
//!    while some drop is taken. Typical cases: a thin cap lying across
//!    several blocks, which no single neighbour's milled shape can take
//!    without colliding with the others; a thin wall inside the model.
//! 2. MERGED into a touching block otherwise: the two replaced by the MILLED
//!    SHAPE of their union along one of the six directions, under exactly the
//!    tests of merge_within_tolerance() (closed 2-manifold, exact height
//!    field, height and machine limits; the model then made measured within
//!    T by FillDeviationMeter, measure + error bound <= T; no overlap with
//!    any other block, exact volume <= 1e-6 of the smaller), with a wider
//!    direction screen, the size caps raised (a sliver is worth a slow
//!    measure), and a union whose rounding to doubles leaves zero-area faces
//!    cleaned as export cleans every block (clean_rounded_block(), its
//!    1e-10 x scale added to the bound) instead of rejected. Only pairs
//!    holding a sliver are tried. Typical case: a slab reaching past its
//!    neighbour (a drop would uncover the input there).
//! 3. SPLIT otherwise, when its pieces can go: the sliver is cut across the
//!    plane of one of its own axis-aligned faces strictly inside its box
//!    (where a thin sheet and a thick part of it meet; the planes with the
//!    most face area first, at most `max_split_planes`) by an exact clip to
//!    the two half-spaces; each piece must round to doubles without
//!    degenerate or flipped faces and be an exact height field along the
//!    sliver's axis (its own milled shape). Steps 1 and 2 then run on the
//!    pieces that are slivers (the pieces alone), and the split is kept
//!    when it leaves fewer slivers in all; else the next plane. The pieces
//!    make up the sliver (the clip is exact), so only the drops and merges
//!    of pieces deviate, measured as above. Typical case (fertility at
//!    1e-3, block 020): a sheet 0.44 T thick glued between two blocks, with
//!    a lump 1.5-2.2 thick at one end that holds the input surface: the
//!    lump forbids the drop (the input beside it 3.2 T from the other
//!    blocks) and every merge (milled shapes 2-32 T off the input, or
//!    colliding), but the sheet alone drops within 0.3 T and the lump alone
//!    is no sliver.
//! 4. THICKENED otherwise (decompose() runs this stage on its own,
//!    thicken_slivers(), after its step 9c's exact re-decompositions):
//!    the sliver takes the material of its neighbours
//!    in a slab beyond one of its sides across an axis k (the thinnest
//!    first) that is a
//!    cut plane (a face of it lies in the plane of its box side), over its
//!    footprint, a depth delta deep (max(1.5 (min_thickness - t), 1/4
//!    min_thickness), then min_thickness, then twice: t its mean chord
//!    along k); a neighbour milled across k may give the slab open towards
//!    its tool side, or through its whole extent along its own axis (the
//!    pocket left in it then has no wall over its own material); last, the
//!    model in the slab that no block holds (the interior may stay empty)
//!    joins too. Done exactly (corefinement on the exact
//!    kernel, each result rounded once), so the blocks make up the same
//!    solid (with at most some of the model's interior added) and nothing
//!    deviates; kept when the sliver stays one piece, is
//!    an exact height field along its axis (or another), each neighbour's
//!    remaining pieces are exact height fields along theirs, there are no
//!    more blocks than before, none is a sliver and each passes the
//!    export's check. Typical case (rocker_arm.obj at 5e-4, block 51): a
//!    cap 0.35 T thick on the model's flank, milled across its thin axis,
//!    whose drop uncovers the input (1.7 T) and whose neighbours' milled
//!    unions stray 2 T: the cap is deepened into the block under it.
//!    kitten.obj at 5e-4 (block 55): a rod whose cut faces face the model's
//!    empty interior, deepened into it.
//! A sliver none of them removes is kept and reported (decomposition.json
//! "num_slivers", validate check 9). At T = 0 nothing may deviate and the
//! exact merges (merge_blocks) have already joined every pair whose union is
//! a block, so only the thickening (4., exact) runs; the slivers left are
//! counted and reported; at the command's default decompose() then
//! runs this stage again on the exact blocks within 1, 2 or 5 x 1e-4 of the
//! diagonal (the fallback tolerance at most; decompose.h).
//! Deterministic whatever the thread count.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <limits>
#include <vector>

#include "subfab/core/progress.h"
#include "subfab/decompose/carve_blocks.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of remove_slivers().
struct SliverRemovalOptions {
  double min_thickness = 0.0;  // model units (> 0): blocks thinner than this where the model is thicker are slivers
  double tolerance = 0.0;      // T, model units (>= 0): 0 = exact, slivers are only reported
  double error_fraction = 0.05;  // error bound of the distance measures, fraction of T, in (0, 1)
  double max_height = std::numeric_limits<double>::infinity();  // block extent along its axis, model units
  Vec3 machine_size = Vec3::Constant(std::numeric_limits<double>::infinity());  // X, Y, Z work volume, model units
  double screen_factor = 4.0;  // merges: a direction is not tried when the material it would leave under a face is
                               // thicker than this x T (merge_within_tolerance's screen, a heuristic that saves
                               // time: 4x its default)
  std::size_t max_pair_faces = 60000;    // a sliver's pair with more faces in all is not tried (merge_within_tolerance's
                                         // cap, raised 5x)
  std::size_t max_region_faces = 80000;  // a merge whose deviation would be measured over more input faces is not
                                         // taken (merge_within_tolerance's cap, raised 4x)
  std::size_t max_split_planes = 6;      // splits: planes tried per sliver left (remove_slivers.h, 3.)
  bool thicken = true;                   // thickenings of the slivers left (remove_slivers.h, 4.)
  std::size_t max_thicken_tries = 30;         // thickenings: tries per sliver at most, a bound on the cost
                                             // (without it decimated_knight's 36 exact slivers took 1425 tries,
                                             // 10 min, for 3 thickened)
  std::size_t max_thicken_tries_total = 300; // thickenings: tries per call at most, over every sliver
  std::size_t max_thicken_faces = 2000;  // thickenings: a sliver, or a neighbour's part in its region, with more
                                         // faces is not tried (CGAL's corefinement of a large part touching the
                                         // sliver along a plane ran over 30 minutes, unfinished, on rotor's fallback:
                                         // a 3462-face sliver and a 2388-face part; the slivers removed so far
                                         // have 70-114 faces)
  const std::vector<char>* filled = nullptr;  // per input block: 1 when it sticks out of the solid; nullptr: none
  std::function<std::string(const Block&)> block_defect;  // merges: the export's check of a merged block
                               // (merge_within_tolerance's option of that name); empty: not checked
  Progress* progress = nullptr;  // progress and info (nullptr: silent)
};

//! Result of remove_slivers().
struct SliverRemovalResult {
  std::vector<Block> blocks;   // exact height fields, canonical frame
  std::vector<char> filled;    // per block: 1 when it sticks out of the solid (empty when the input's was nullptr
                               // and nothing was merged)
  std::size_t num_found = 0;   // slivers among the input blocks
  std::size_t num_merged = 0;  // merges that absorbed a sliver
  std::size_t num_dropped = 0; // slivers dropped (pieces of split slivers included)
  std::size_t num_split = 0;   // slivers split into pieces that were then merged or dropped
  std::size_t num_thickened = 0;  // slivers thickened with their neighbours' material (nothing deviates)
  std::size_t num_left = 0;    // slivers among the output blocks
  double max_deviation = 0.0;  // largest deviation bound of an applied merge or drop, model units
};

//! Finds the slivers of `blocks` and drops, merges or splits each within
//! the tolerance (see the file comment).
//! \param solid  the solid the blocks were carved from (canonical frame)
//! \param blocks exact height-field blocks of `solid`, canonical frame
//! \throw InvalidArgumentError when min_thickness <= 0, T < 0 or the filled flags do not match the blocks.
SliverRemovalResult remove_slivers(const Mesh& solid, std::vector<Block> blocks, const SliverRemovalOptions& options);

//! Stage 4 of remove_slivers() alone (the thickening, see the file
//! comment; exact, at any tolerance), on the slivers of `blocks`:
//! decompose() runs it after its step 9c's re-decompositions, which may
//! save a block where the thickening only keeps the count. The result's
//! num_found, num_thickened, num_left, max_deviation (the cleanup's, at T >
//! 0) and blocks / filled are set. \throw InvalidArgumentError as remove_slivers().
SliverRemovalResult thicken_slivers(const Mesh& solid, std::vector<Block> blocks, const SliverRemovalOptions& options);

//! Per block of `blocks` (canonical frame): 1 when it is a sliver of
//! `solid` at `min_thickness` (find_slivers() in the canonical frame, whose
//! axes are the blocks' machine axes), in parallel.
std::vector<char> sliver_flags(const Mesh& solid, const std::vector<Block>& blocks, double min_thickness);

}  // namespace subfab
