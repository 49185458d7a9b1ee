// SPDX-License-Identifier: GPL-3.0-or-later
//! \file read_skeleton.h
//! Reading a curve-skeleton in the `.skel` text format (Livesu et al. 2012,
//! as used by Skeleton Lab and the thesis's Appendix D):
//!
//!     ID Cx Cy Cz RADIUS #NEIGHBORS NEIGHBORS_LIST      (header line)
//!     N                                                  (node count)
//!     id x y z r n nbr_1 ... nbr_n                       (N lines, id = 0..N-1)
//!
//! Blank lines and lines starting with '#' are ignored; the header line is
//! optional. Neighbour lists must be symmetric.
#pragma once

#include <filesystem>
#include <istream>

#include "subfab/hex/skeleton.h"

namespace subfab {

//! Reads a `.skel` file.
//! \throw IoError when the file cannot be opened or is malformed (missing
//!        node count, wrong id, bad number, neighbour index out of range,
//!        asymmetric adjacency); the message names the file and the line.
Skeleton read_skeleton(const std::filesystem::path& path);

//! Same, from a stream; `name` is used in messages.
Skeleton read_skeleton(std::istream& in, const std::string& name);

}  // namespace subfab
