// SPDX-License-Identifier: GPL-3.0-or-later
//! \file block_name.h
//! How messages name a block of a decomposition.
#pragma once

#include <cstddef>
#include <string>

namespace subfab {

//! "block NNN" (zero-padded to three digits), the number of its files
//! blocks/block_NNN.obj and mill/block_NNN.stl.
std::string block_name(std::size_t i);

}  // namespace subfab
