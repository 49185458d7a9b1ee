// SPDX-License-Identifier: GPL-3.0-or-later
//! \file deterministic_arena.h
//! Private: makes CGAL's exact booleans give the same triangulation whatever
//! thread runs them.
//!
//! CGAL's corefinement breaks ties between equal bounding-box coordinates
//! by comparing box ADDRESSES (Box_intersection_d::ID_FROM_BOX_ADDRESS), and
//! our axis-aligned boxes create such ties all the time. The order of heap
//! addresses depends on which thread allocated what before, so the same
//! boolean run on another thread could triangulate its cut faces
//! differently. While a DeterministicArena lives, every `operator new` of
//! the current thread is served by a private bump allocator over one
//! reserved address range: addresses then follow from the thread's sequence
//! of allocations and frees, which is a property of the computation alone.
//! Freed blocks are reused (per size class, last freed first), so the arena
//! holds about the computation's live peak; the address range is given back
//! when the arena ends, all at once.
//!
//! Rules: every object allocated while the arena is active must be
//! destroyed before the arena ends (results the caller keeps must be built
//! under a SuspendArena), and exceptions must not carry arena strings out.
#pragma once

#include <cstddef>
#include <exception>
#include <string>

namespace subfab::detail {

//! RAII: the current thread allocates from a fresh private arena.
class DeterministicArena {
 public:
  //! \param reserve_bytes address space reserved (not committed) for the arena
  //! \param reuse_freed false: a pure bump allocator (addresses grow with
  //!        allocation order; nothing freed is reused before the arena ends)
  explicit DeterministicArena(std::size_t reserve_bytes = std::size_t{64} << 30, bool reuse_freed = true);
  ~DeterministicArena();
  DeterministicArena(const DeterministicArena&) = delete;
  DeterministicArena& operator=(const DeterministicArena&) = delete;
  //! Bytes handed out so far.
  std::size_t used_bytes() const;
  //! False when the address range could not be reserved (then nothing changes).
  bool active() const;

 private:
  void* state_;
};

//! RAII: while it lives, new allocations of this thread come from the normal
//! heap again (frees of arena memory are still recognised).
class SuspendArena {
 public:
  SuspendArena();
  ~SuspendArena();
  SuspendArena(const SuspendArena&) = delete;
  SuspendArena& operator=(const SuspendArena&) = delete;

 private:
  bool was_active_;
};

//! Runs `work()` in a fresh DeterministicArena and catches every
//! std::exception inside it, so that no arena string leaves the arena:
//! returns the exception's message copied to the heap ("unknown error" when
//! it has none), or an empty string when `work` returned normally.
//! Whatever `work` hands back must be built under a SuspendArena.
template <class Work>
std::string run_in_arena(Work&& work, bool reuse_freed = true) {
  std::string error;
  {
    DeterministicArena arena(std::size_t{64} << 30, reuse_freed);
    try {
      work();
    } catch (const std::exception& e) {
      SuspendArena heap;
      error = e.what();
      if (error.empty()) error = "unknown error";
    }
  }
  return error;
}

}  // namespace subfab::detail
