// SPDX-License-Identifier: GPL-3.0-or-later
//! \file edge_key.h
//! Private: the hash-map key of a directed edge a -> b between two vertex
//! ids, shared by the polygonal-mesh code of the unfoldable simplification
//! (thesis Chapter 3): facet deletion, its exact checks, the nets and their
//! drawing. edge_key(b, a) is the opposite edge's key.
#pragma once

#include <cstdint>

namespace subfab::unfold_detail {

//! Key of the directed edge a -> b: a in the high 32 bits, b in the low ones.
inline std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

}  // namespace subfab::unfold_detail
