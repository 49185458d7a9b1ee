// SPDX-License-Identifier: GPL-3.0-or-later
//! \file box_pieces.h
//! How many blocks a height box would give on its own (the carve stage turns
//! every connected piece of solid ∩ box that touches the surface into its
//! own block). Used between grow and cover so
//! that the minimal cover counts blocks, not boxes (thesis 4.3.2 minimises
//! boxes; a box whose region falls into k pieces costs k blocks, which is
//! where most of the blocks beyond the cover came from on thin models:
//! airplane wing tips and fins, kitten at a low height limit).
//!
//! The count is a predictor for the cover's costs, not a validity decision:
//! it is the number of connected components of the surface inside the box
//! (faces meeting the open box, or covered by it), two faces being connected
//! when they share an edge that meets the closed box (double-precision
//! segment/box test). Deterministic.
#pragma once

#include <vector>

#include "geometry/solid_index.h"
#include "subfab/geometry/height_box.h"

namespace subfab::detail {

//! Edge adjacency of a closed manifold mesh: neighbour[3 f + k] is the face
//! across edge k (vertices k, k+1) of face f, or -1.
std::vector<int> face_neighbours(const Mesh& mesh);

//! Connected pieces of the surface inside `box` (see the file comment): per
//! piece, its sorted face ids. Pieces are ordered by their smallest face id.
std::vector<std::vector<int>> surface_pieces(const SolidIndex& index, const std::vector<int>& neighbours,
                                             const HeightBox& box);

}  // namespace subfab::detail
