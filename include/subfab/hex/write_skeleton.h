// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_skeleton.h
//! Writing a curve-skeleton in the `.skel` text format (see read_skeleton.h).
#pragma once

#include <filesystem>
#include <ostream>

#include "subfab/hex/skeleton.h"

namespace subfab {

//! Writes `skeleton` to `out` (header line, node count, one line per node,
//! coordinates with 17 significant digits so that reading it back is exact).
void write_skeleton(const Skeleton& skeleton, std::ostream& out);

//! Writes `skeleton` to the file `path`. \throw IoError when it cannot.
void write_skeleton(const Skeleton& skeleton, const std::filesystem::path& path);

}  // namespace subfab
