// SPDX-License-Identifier: GPL-3.0-or-later
//! \file snap_and_shrink_detail.h
//! snap_and_shrink() on a prebuilt SolidIndex (the pipeline builds one).
#pragma once

#include "geometry/solid_index.h"
#include "subfab/decompose/snap_and_shrink.h"

namespace subfab::detail {

//! Same contract as subfab::snap_and_shrink().
SnapShrinkResult snap_and_shrink(const SolidIndex& index, std::vector<HeightBox> boxes,
                                 const SnapShrinkOptions& options);

}  // namespace subfab::detail
