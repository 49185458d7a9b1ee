// SPDX-License-Identifier: GPL-3.0-or-later
//! \file box_tests.h
//! Private: whether two bounding boxes meet, the one test the systems share
//! (decompose's block pairs, validate's overlap and fill measures).
#pragma once

#include "subfab/mesh/mesh.h"

namespace subfab::detail {

//! Do the closed boxes a and b meet (touching counts)?
inline bool boxes_touch(const BoundingBox& a, const BoundingBox& b) {
  return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}

//! Do the open interiors of the boxes a and b meet (touching does not count)?
inline bool interiors_meet(const BoundingBox& a, const BoundingBox& b) {
  return (a.min.array() < b.max.array()).all() && (b.min.array() < a.max.array()).all();
}

}  // namespace subfab::detail
