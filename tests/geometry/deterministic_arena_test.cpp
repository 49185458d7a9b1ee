// SPDX-License-Identifier: GPL-3.0-or-later
#include "geometry/deterministic_arena.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace subfab::detail {
namespace {

// The offsets of a fixed sequence of allocations and frees from the arena's
// first allocation: what decides the order of addresses CGAL compares.
std::vector<std::ptrdiff_t> offsets_of_a_sequence(bool reuse) {
  std::vector<std::ptrdiff_t> out;
  out.reserve(200);  // the result outlives the arena: no allocation of it inside
  DeterministicArena arena(std::size_t{1} << 30, reuse);
  EXPECT_TRUE(arena.active());
  char* first = new char[24];
  std::vector<char*> live;
  live.reserve(200);
  for (int i = 0; i < 200; ++i) {
    char* p = new char[static_cast<std::size_t>(8 + (i * 37) % 3000)];
    out.push_back(p - first);
    live.push_back(p);
    if (i % 3 == 2) {  // free one of the older blocks
      delete[] live[static_cast<std::size_t>(i / 2)];
      live[static_cast<std::size_t>(i / 2)] = nullptr;
    }
  }
  for (char* p : live) delete[] p;
  delete[] first;
  return out;
}

TEST(DeterministicArena, TheSameSequenceGivesTheSameAddressOrder) {
  EXPECT_EQ(offsets_of_a_sequence(true), offsets_of_a_sequence(true));
  EXPECT_EQ(offsets_of_a_sequence(false), offsets_of_a_sequence(false));
}

// A temporary allocated and freed over and over (CGAL's lazy kernel inside one
// boolean) must not grow the arena: a pure bump allocator grew to 10 GB.
TEST(DeterministicArena, FreedBlocksAreReused) {
  std::size_t used_reuse = 0, used_bump = 0;
  for (bool reuse : {true, false}) {
    DeterministicArena arena(std::size_t{1} << 30, reuse);
    ASSERT_TRUE(arena.active());
    std::vector<std::unique_ptr<double[]>> keep;
    for (int i = 0; i < 10000; ++i) {
      auto tmp = std::make_unique<double[]>(static_cast<std::size_t>(1 + i % 50));  // freed at once
      tmp[0] = i;
      if (i % 1000 == 0) keep.push_back(std::make_unique<double[]>(4));
    }
    (reuse ? used_reuse : used_bump) = arena.used_bytes();
    keep.clear();  // every arena object dies before the arena
  }
  EXPECT_LT(used_reuse, std::size_t{16} << 10);     // the 50 size classes once, plus the kept blocks
  EXPECT_GT(used_bump, std::size_t{1} << 20);       // 10000 blocks of 8-400 bytes
  // an over-aligned block, and memory written through it
  DeterministicArena arena(std::size_t{1} << 30);
  struct alignas(64) Wide {
    double v[8];
  };
  auto w = std::make_unique<Wide>();
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(w.get()) % 64, 0u);
  w->v[7] = 1.0;
  EXPECT_EQ(w->v[7], 1.0);
}

}  // namespace
}  // namespace subfab::detail
