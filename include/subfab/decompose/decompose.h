// SPDX-License-Identifier: GPL-3.0-or-later
//! \file decompose.h
//! The whole height-field block decomposition of thesis Chapter 4:
//!
//!   orient (4.3.1) -> fields (4.3.2) -> grow boxes (4.3.2, App. B)
//!   -> minimal cover (4.3.2, CBC) -> snap and shrink (4.3.4) -> resolve overlaps (4.3.3: conflict
//!   graph, cycle splits, carve order) -> carve (exact booleans)
//!   -> merge (4.3.4 post-processing) [-> merges within the tolerance, issue 17]
//!   -> no slivers (issue 17: remove_slivers.h)
//!
//! Everything happens in the canonical frame (canonical = rotation x input);
//! export_decomposition() writes the blocks back in the input's frame.
#pragma once

#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "subfab/core/progress.h"
#include "subfab/decompose/carve_blocks.h"
#include "subfab/fidelity/repair_infeasible_features.h"
#include "subfab/geometry/rotate_into_frame.h"
#include "subfab/mesh/mesh.h"

namespace subfab {

//! Options of decompose() (the `subfab decompose` options).
struct DecomposeOptions {
  double max_height_fraction = std::numeric_limits<double>::infinity();  // --max-height: x bbox diagonal (inf = none)
  double max_height_abs = std::numeric_limits<double>::infinity();       // --max-height-abs: model units (inf = none)
  std::optional<Vec3> machine;  // --machine X,Y,Z: work volume, model units; Z along the milling direction
  bool orient = true;           // false: --no-orient, keep the input frame
  double grid_factor = 1.0;     // --grid-factor: grid spacing = average edge length x this (> 0)
  double cover_time_limit_s = 60.0;  // CBC time limit, seconds
  bool merge = true;            // merge touching blocks whose union is a valid block along some direction (4.3.4)
  bool repair = true;           // false: --exact, refuse (AlgorithmError) when the chosen frame has infeasible
                                // features instead of repairing them (repair_infeasible_features, 4.3.5)
  double max_deviation = 0.005; // --max-deviation: cap on the repair's Hausdorff distance, x bbox diagonal (> 0)
  // Cap on the orientation's precision snap (x bbox diagonal; 0 = never snap
  // beyond the 1e-9 frame snap): a frame infeasible only through the file's
  // own coordinate rounding is snapped by 4 x that rounding, at most this
  // (orient_mesh(), OrientOptions::precision_snap_tolerance). Files with 6
  // significant digits need 1e-6 to 8e-6; the cap keeps coordinates that are
  // round numbers by design (a part drawn on a 1 mm grid reads as 1 digit,
  // +-0.5 mm) from being snapped by their apparent rounding.
  double max_precision_snap = 1e-5;
  double max_overhang_deg = 0.0; // --max-overhang: faces may lean up to this many degrees past vertical off the
                                 // base ([0, 45]; 0 = exact height fields). A 3-axis machine cannot cut such
                                 // faces (it leaves material under them); the thesis's blocks have them.
                                 // The frame search and the thin-feature repair stay exact (conservative).
  double tolerance_fraction = 0.0;  // --tolerance: deviation allowed, x bbox diagonal (0 = exact blocks only, the
                                    // thesis's exact decomposition); see merge_within_tolerance()
  double tolerance_abs = std::numeric_limits<double>::infinity();  // --tolerance-abs: model units; the smaller of
                                    // the two wins, so a tolerance in model units alone needs tolerance_fraction
                                    // set too (1.0: a whole diagonal, as the command does for --tolerance-abs
                                    // alone); with tolerance_fraction 0 the blocks are exact
  double fallback_tolerance_fraction = 0.0;  // at tolerance 0: when the thin-feature repair (4.3.5) gives up,
                                    // or the exact blocks include slivers (thinner than 1e-4 x diagonal where
                                    // the model is thicker; then also the exact blocks with their slivers
                                    // dropped or merged within at most this tolerance; see decompose()),
                                    // decompose again within this tolerance (x bbox diagonal) instead of failing:
                                    // the features' faces may lean where their undercuts are within it, the
                                    // blocks are milled and measured as with --tolerance (issue 17, "every closed
                                    // model gets blocks"). 0 (the library's default): AlgorithmError. The command
                                    // sets 5e-4 unless --tolerance, --tolerance-abs, --exact, --max-overhang or
                                    // --smooth is given (a hobby machine holds about 0.1 mm on a 200 mm part)
  double fallback_min_carve_gain = 0.05;  // at tolerance 0 with exact blocks that have slivers, when the in-place
                                    // removal within 1-5e-4 already left none: the whole re-decomposition within the
                                    // fallback tolerance is given up (the in-place blocks kept) after a round whose
                                    // carve has at least (1 - this) x the exact carve's blocks, before that round is
                                    // milled and measured ([0, 1); 0 = never given up). A count, so deterministic;
                                    // a prediction, not a bound: later merges within the tolerance could still
                                    // gain (pinion: 1454 of 1485, given up; couplingdown: 3, 30, 31, 123 of 191,
                                    // 56 blocks at the end vs 107 in place; bench/RESULTS.md)
  double tolerance_exact_margin = 0.25;  // within a tolerance, when no feature needs an allowance: the exact
                                    // decomposition is made first, and a round under allowances whose carve has at
                                    // least max(E + 2, (1 + this) x E) blocks (E: the exact count) is given up
                                    // before it is milled and measured, the exact blocks kept. A count, so
                                    // deterministic; a prediction, not a bound (merges after the measure could still
                                    // gain). Moai at 3.8e-4: 9 carved against 7 exact, the 14 s measure saved.
                                    // < 0: never given up
  int tolerance_rounds = 4;         // within a tolerance: decompositions under allowances (tolerance_allowances())
                                    // before the exact one (>= 1)
  bool tolerance_local_exact = true;  // within a tolerance, when the last round still has blocks beyond it: each
                                    // such block's carved piece is decomposed again on its own, within the tolerance
                                    // and, where that fails too, exactly (the others kept, those near a change
                                    // measured again); false, or when a piece cannot be decomposed on its own: the
                                    // whole model is decomposed again without allowances (the pinned ones kept)
  std::vector<double> tolerance_depth_fractions = {2.0, 1.0, 0.5};  // within a tolerance: a face may lean past
                                    // vertical when its undercut depth <= q x T, q first the first of these (> 0,
                                    // unitless); where a block's milled shape fails the measure, the faces in its
                                    // box step to the next q, then to none. A heuristic: the measure decides
  double sliver_thickness = 1e-4;  // blocks thinner than max(this x bbox diagonal, the tolerance) where the model
                                   // is thicker are slivers (validate check 9): within a tolerance they are merged
                                   // or dropped where measured within it, at 0 only counted (remove_slivers.h)
  double tolerance_floor_scale = 0.25;  // within a tolerance: a face whose undercut is deeper than q x T may still
                                    // lean in boxes whose base lies at most this x q x T / |n.d| under its top (the
                                    // fill there is that short; allowances_with_floors(); --tolerance-floors; >= 0,
                                    // unitless). Where a block fails the measure, its faces' levels step down (floors
                                    // shrink with them); after tolerance_rounds, the exact path. 0: per face only. 0.25 (the default):
                                    // never more blocks than per face on the models measured, often far fewer
                                    // (airplane at 1.8e-3 9 vs 18, cube spike at 9.8e-4 and height 0.4 5 vs 6;
                                    // bench/RESULTS.md); 0.5 and 1 fail the measure on curved undersides
  bool tolerance_carry_boxes = true;  // within a tolerance: a round after a failing one starts from the boxes of
                                    // the blocks that passed (those still valid under the lowered allowances: grow
                                    // seeds only where none holds), so a round changes the decomposition where
                                    // blocks failed and little elsewhere (false: every round grown afresh, before
                                    // session 35)
  double tolerance_locate_margin = 1.0;  // within a tolerance, where a block fails by a sampled point farther than T
                                    // (the lower bound's): only the faces allowed along its axis whose boxes,
                                    // widened across the axis by this x T, lie over such a point (within the
                                    // block's box) step down a level, not every face in its box (>= 0, unitless;
                                    // the block's whole box where none is found, or for another failure); < 0:
                                    // the whole box always (before session 35)
  std::vector<double> tolerance_overhang_ladder_deg = {5, 10, 15, 20, 30, 45};  // within a tolerance, when the
                                    // blocks deviate at most tolerance_ladder_slack x T: decompositions where every
                                    // face leaning at most this many degrees past vertical may lean
                                    // (uniform_overhang_allowances()), each angle in turn; one whose carve has fewer
                                    // blocks is milled, measured and kept when every milled shape passes and, after
                                    // the exact merges, it still has fewer; the ladder ends at the first that fails
                                    // the measure, passes with a deviation above the slack, or carves at least
                                    // max(B + 2, (1 + tolerance_exact_margin) B) blocks, B the best so far (not with
                                    // a margin < 0) (increasing, each in (0, 45]; empty: no ladder). The depth
                                    // allowances bound a face's undercut by the free length under it, far deeper
                                    // than the fill a block has when its base lies close under the face (cube spike
                                    // at 9.8e-4: 5 blocks, with the ladder 2 at 10 deg, as the thesis's 2)
  double tolerance_ladder_slack = 0.5;  // the ladder runs (and goes on) while the blocks' measured deviation is at
                                    // most this x T
                                    // ([0, 1]): where it is already near T (the statues), a larger allowance is not
                                    // expected to pass, and the ladder's carves would only cost time
  Progress* progress = nullptr; // stage progress (nullptr = silent)
};

//! Wall time of each stage, seconds.
struct DecomposeTimings {
  double orient = 0, field = 0, grow = 0, cover = 0, resolve = 0, carve = 0, total = 0;
  double repair = 0;  // local repair of infeasible features (0 when none), not part of orient
  double tolerance = 0;  // merges within the tolerance (merge_within_tolerance), part of carve
};

//! Result of decompose().
struct DecomposeResult {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // canonical = rotation x input
  Mesh canonical;            // the (possibly locally refined) input in the canonical frame (rotate_into_frame: turned, near-equal coordinates snapped)
  std::size_t num_input_vertices = 0;  // canonical vertices [0, this) are the input's (or repaired input's) vertices, same ids
  // Set when the chosen frame had infeasible features and they were repaired
  // (options.repair): the repaired solid in INPUT coordinates (vertices of
  // unchanged faces keep the input's exact coordinates), same vertex ids as
  // the canonical mesh before grow; the blocks decompose it, not the input.
  std::optional<Mesh> repaired_input;
  RepairReport repair;       // what the repair found and changed (num_features = 0: nothing repaired)
  // rotate_into_frame()'s snap for the chosen frame (fraction of the turned
  // bounding-box diagonal): kFrameSnapTolerance, or, when only that made the
  // frame feasible, 4 x the file's own coordinate rounding (orient_mesh(),
  // OrientOptions::precision_snap_tolerance). Then repaired_input is the input
  // with those coordinates snapped (back in input coordinates), `repair` has
  // num_features = 0 and the largest / mean vertex move as its deviations.
  double frame_snap_tolerance = kFrameSnapTolerance;
  double coordinate_rounding = 0;         // coordinate_rounding() of the input (model units; 0 = full precision)
  std::size_t num_snapped_vertices = 0;   // input vertices the precision snap moved (0 when it was not used)
  double max_height = std::numeric_limits<double>::infinity();  // the height limit used (model units)
  double max_overhang_deg = 0.0;  // the overhang allowance used (degrees; 0 = exact)
  std::vector<Block> blocks; // the blocks, canonical frame
  std::vector<HeightBox> ordered_boxes;  // the boxes the last carve used, in carve order (canonical frame;
                                         // Block::source_box indexes them): decompose_smoothed() carves again
  double tolerance = 0.0;    // the deviation allowed (model units; 0 = exact: every block inside the input)
  std::vector<char> filled;  // per block (empty when tolerance = 0): 1 when it sticks out of the input (a milled
                             // shape holding material under an undercut, within the tolerance)
  double deviation_bound = 0.0;  // largest deviation bound measured by the merges within the tolerance (model units)
  std::size_t num_tolerance_merges = 0;  // merges into milled shapes within the tolerance
  std::size_t num_allowed_faces = 0;     // faces first allowed to lean past vertical in every box (tolerance_allowances())
  std::size_t num_floored_faces = 0;     // faces first allowed to lean only in boxes whose base lies close enough
                                         // under them (allowances_with_floors())
  int num_tolerance_rounds = 0;          // decompositions under allowances that were milled and measured
  double tolerance_overhang_deg = 0.0;   // the overhang ladder's angle whose blocks were kept (degrees; 0: none)
  std::size_t num_blocks_decomposed_in_place = 0;  // blocks of the last round still beyond the tolerance whose
                                         // carved pieces were decomposed again on their own (tolerance_local_exact)
  double sliver_thickness = 0.0;         // the sliver threshold used (model units; remove_slivers.h)
  std::size_t num_slivers = 0;           // slivers among the output blocks (kept: nothing removes them within T)
  std::size_t num_slivers_merged = 0;    // slivers merged into a neighbour within the tolerance
  std::size_t num_slivers_dropped = 0;   // slivers dropped within the tolerance
  std::size_t num_slivers_thickened = 0; // slivers thickened with their neighbours' material (exact, any tolerance)
  std::size_t num_slivers_recarved = 0;  // slivers decomposed again exactly together with a neighbour (step 9c)
  std::string tolerance_fallback;  // set when the thin-feature repair gave up at tolerance 0, or the exact
                                   // blocks had slivers, and the result was made within
                                   // options.fallback_tolerance_fraction instead: why (the repair's message, or
                                   // the slivers' count); empty otherwise
  std::size_t num_features_within_tolerance = 0;  // infeasible features (creases, spikes) left to the tolerance
                                                  // instead of the thin-feature repair (their faces' allowances
                                                  // pinned); 0 when none or when they were repaired
  DecomposeTimings timings;
  // statistics
  std::size_t num_grown_boxes = 0;
  std::size_t num_selected_boxes = 0;
  std::size_t num_ordered_boxes = 0;   // after cycle splits
  std::size_t num_carved_blocks = 0;   // blocks the last carve made (before the merges)
  int num_refined_faces = 0;
  int num_cycle_splits = 0;
  std::size_t num_merges = 0;
  bool cover_optimal = false;
};

//! Decomposes a closed solid into height-field blocks (thesis Chapter 4).
//! \param input closed, manifold, outward-oriented, self-intersection-free mesh
//!        (pass it through require_closed_solid first)
//! When the chosen frame has features no height-field box can cover
//! (find_infeasible_features()), they are repaired locally first
//! (repair_infeasible_features(), thesis 4.3.5; result.repaired_input), or,
//! with options.repair = false, an AlgorithmError lists them. Within a
//! tolerance (T > 0, issue 17) the features whose faces may lean past
//! vertical (undercut within the tolerance, tolerance_allowances()) are not
//! repaired: those faces' allowances are pinned (never lowered) and the
//! blocks holding them are milled and measured like the others; only when
//! those blocks still fail the measure with no other allowance left, or
//! when some feature's faces are not allowed, are the features repaired.
//! Every block is an exact height field whatever T. At T = 0 with
//! options.fallback_tolerance_fraction > 0 (and options.repair), a repair
//! that gives up is followed by the decomposition within that tolerance
//! (result.tolerance_fallback says why; progress warns). Exact blocks with
//! slivers (issue 17, "no slivers") fall back two ways: the whole model
//! decomposed again within that tolerance, and the exact blocks with the
//! sliver stage run again within the smallest of 1, 2, 5 x 1e-4 of the
//! diagonal (up to that tolerance) that removes them all; of those without
//! slivers the one with fewer blocks is kept (the exact blocks on a tie),
//! else the exact one, slivers counted. When the in-place removal left no
//! sliver, the whole re-decomposition is given up after a round whose carve
//! has at least fallback_carve_limit() blocks (options.fallback_min_carve_gain).
//! \throw InvalidArgumentError on bad options; AlgorithmError when a stage fails.
DecomposeResult decompose(const Mesh& input, const DecomposeOptions& options);

//! The rule that bounds the default's re-decomposition (decompose(), when
//! the exact blocks' slivers were all removed in place): the number of
//! carved blocks at which a round of the re-decomposition within the
//! fallback tolerance is given up, ceil((1 - min_gain) x exact_carved)
//! (DecomposeOptions::fallback_min_carve_gain); 0 (never given up) when
//! min_gain is 0 or nothing was carved.
std::size_t fallback_carve_limit(std::size_t exact_carved, double min_gain);

}  // namespace subfab
