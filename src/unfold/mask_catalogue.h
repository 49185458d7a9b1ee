// SPDX-License-Identifier: GPL-3.0-or-later
//! \file mask_catalogue.h
//! The simplification masks of thesis Appendix A, described as data and
//! expanded to every orientation by program.
//!
//! A mask is a pattern of lattice signs around an anchor point plus one or
//! more sets of Points of Interest (POI): flipping all the points of one set
//! removes or moves the local configuration (thesis Section 3.3.1). The
//! figures of Appendix A are not available (only their captions), so the base
//! types are our reading of the captions:
//! - Figures A.1-A.7 (several POI sets): "a step between two facets of
//!   category a and a facet of category b": a one-unit terrace, i.e. the
//!   half-space n.p <= 0 lowered to n.p <= -1 over a region R bounded by a
//!   lattice half-plane h.p >= 0 (R = the points with every h.p >= 0). The
//!   riser between the two terrace levels is the facet of the other
//!   category. POI sets: {anchor -> inside} grows the upper facet over the
//!   riser; {b -> outside} for each 6-neighbour b of the anchor on the upper
//!   level outside R grows the lower facet.
//! - Figures A.8-A.11 (one POI set): "pyramids": a bump (extra inside points
//!   just above a lattice plane n.p <= -1) or a pit (missing points just
//!   below n.p <= 0); the POI set is the bump or pit itself.
//! Orientations: the 48 signed axis permutations (rotations and reflections
//! of the cube) applied to each base type; identical results are kept once.
//! With the types below this gives exactly the counts of the captions
//! (A.1 24, A.2 24, A.3 48, A.4 48, A.5 24, A.6 24, A.7 48, A.8 12, A.9 24,
//! A.10 16, A.11 48: 340 masks) and 18 masks up to rotation.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace subfab::masks {

using Offset = std::array<int, 3>;

//! One oriented mask.
struct Mask {
  int base_type = 0;                         // index into base_types()
  std::vector<std::pair<Offset, bool>> signs;  // required sign (true = inside) at anchor + offset
  std::vector<std::vector<Offset>> poi_sets;   // flipping every point of one set is a move
};

//! A base type as data (see the file comment).
struct BaseType {
  std::string figure;              // "A.1" ... "A.11"
  enum Kind { Terrace, Bump, Pit } kind = Terrace;
  Offset normal{0, 0, 1};          // the plane's lattice normal n
  std::vector<Offset> region;      // Terrace: half-planes h (R = all h.p >= 0)
  std::vector<Offset> points;      // Bump / Pit: the points above / below the plane
};

//! The base types (our reading of Appendix A), in figure order.
const std::vector<BaseType>& base_types();

//! Every distinct orientation of every base type (generated once).
const std::vector<Mask>& oriented_masks();

//! Number of orientations of each base type (same order as base_types()).
std::vector<std::size_t> orientations_per_base_type();

//! Number of masks of each base type up to rotation only: 2 for a chiral
//! type (the thesis draws it and its mirror image as two masks), else 1.
//! The thesis's "18 types" is the sum.
std::vector<std::size_t> rotation_classes_per_base_type();

}  // namespace subfab::masks
