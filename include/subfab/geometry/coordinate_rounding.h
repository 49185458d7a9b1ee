// SPDX-License-Identifier: GPL-3.0-or-later
//! How precisely a mesh file stored its coordinates, for the frame snap of
//! orient_mesh() / decompose() (rotate_into_frame()).
//!
//! CAD exports and many data sets write coordinates with 6 to 9 significant
//! digits (OFF and OBJ writers' "%g") or as float32 (binary STL). A flat face
//! that is exactly planar in the designer's model is then planar only up to
//! that rounding, which exact predicates see: turned into the frame where
//! the face is axis-aligned, its vertices differ by about the rounding along
//! the axis, and exact validity finds tilted faces and creases no
//! axis-aligned block can cover (pinion.off: a spur gear whose caps are
//! planar within 1.4e-6 and whose walls are perpendicular to them within
//! 1.1e-6, coordinates written with 6 digits).
#pragma once

#include "subfab/mesh/mesh.h"

namespace subfab {

//! The largest rounding error of the mesh's coordinates as stored, in model
//! units: with K the most significant decimal digits any coordinate needs
//! (the shortest "%.Kg" that reads back to the same double) and M the
//! largest absolute coordinate, 0.5 x 10^(floor(log10 M) - K + 1) when K <= 9;
//! else, when every coordinate is a float32 value, half a float32 ulp at M
//! (2^-24 x 2^ceil(log2 M)); else 0 (full double precision: no rounding
//! beyond the doubles' own). 0 for an empty mesh or all-zero coordinates.
//! Deterministic; O(#V) formatting work (about 1 us per vertex).
double coordinate_rounding(const Mesh& mesh);

}  // namespace subfab
