// SPDX-License-Identifier: GPL-3.0-or-later
// Replaces the global operator new/delete (all variants) with versions that
// use the calling thread's DeterministicArena when one is active, and the
// C heap otherwise.
#include "geometry/deterministic_arena.h"

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <new>

namespace subfab::detail {
namespace {

struct ArenaState {
  char* base = nullptr;
  char* top = nullptr;
  char* end = nullptr;
  bool allocating = false;
  ArenaState* previous = nullptr;
};

thread_local ArenaState* t_arena = nullptr;

bool owned_by_arena(const void* p) {
  for (const ArenaState* a = t_arena; a; a = a->previous)
    if (p >= a->base && p < a->end) return true;
  return false;
}

void* arena_allocate(ArenaState* a, std::size_t n, std::size_t align) {
  if (n == 0) n = 1;
  auto top = reinterpret_cast<std::uintptr_t>(a->top);
  top = (top + align - 1) & ~(static_cast<std::uintptr_t>(align) - 1);
  if (top + n > reinterpret_cast<std::uintptr_t>(a->end)) throw std::bad_alloc();
  a->top = reinterpret_cast<char*>(top + n);
  return reinterpret_cast<void*>(top);
}

void* heap_allocate(std::size_t n, std::size_t align) {
  if (n == 0) n = 1;
  void* p = nullptr;
  if (align <= alignof(std::max_align_t))
    p = std::malloc(n);
  else if (posix_memalign(&p, align, n) != 0)
    p = nullptr;
  if (!p) throw std::bad_alloc();
  return p;
}

void* allocate(std::size_t n, std::size_t align) {
  if (ArenaState* a = t_arena; a && a->allocating) return arena_allocate(a, n, align);
  return heap_allocate(n, align);
}

void release(void* p) noexcept {
  if (!p || owned_by_arena(p)) return;
  std::free(p);
}

}  // namespace

DeterministicArena::DeterministicArena(std::size_t reserve_bytes) : state_(nullptr) {
  void* base = mmap(nullptr, reserve_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (base == MAP_FAILED) return;
  auto* a = static_cast<ArenaState*>(std::malloc(sizeof(ArenaState)));
  if (!a) {
    munmap(base, reserve_bytes);
    return;
  }
  a->base = static_cast<char*>(base);
  a->top = a->base;
  a->end = a->base + reserve_bytes;
  a->allocating = true;
  a->previous = t_arena;
  t_arena = a;
  state_ = a;
}

DeterministicArena::~DeterministicArena() {
  auto* a = static_cast<ArenaState*>(state_);
  if (!a) return;
  t_arena = a->previous;
  munmap(a->base, static_cast<std::size_t>(a->end - a->base));
  std::free(a);
}

std::size_t DeterministicArena::used_bytes() const {
  const auto* a = static_cast<const ArenaState*>(state_);
  return a ? static_cast<std::size_t>(a->top - a->base) : 0;
}

bool DeterministicArena::active() const { return state_ != nullptr; }

SuspendArena::SuspendArena() : was_active_(t_arena && t_arena->allocating) {
  if (was_active_) t_arena->allocating = false;
}

SuspendArena::~SuspendArena() {
  if (was_active_) t_arena->allocating = true;
}

}  // namespace subfab::detail

using subfab::detail::allocate;
using subfab::detail::release;

void* operator new(std::size_t n) { return allocate(n, alignof(std::max_align_t)); }
void* operator new[](std::size_t n) { return allocate(n, alignof(std::max_align_t)); }
void* operator new(std::size_t n, std::align_val_t al) { return allocate(n, static_cast<std::size_t>(al)); }
void* operator new[](std::size_t n, std::align_val_t al) { return allocate(n, static_cast<std::size_t>(al)); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return allocate(n, alignof(std::max_align_t));
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return allocate(n, alignof(std::max_align_t));
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t n, std::align_val_t al, const std::nothrow_t&) noexcept {
  try {
    return allocate(n, static_cast<std::size_t>(al));
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, std::align_val_t al, const std::nothrow_t&) noexcept {
  try {
    return allocate(n, static_cast<std::size_t>(al));
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { release(p); }
void operator delete[](void* p) noexcept { release(p); }
void operator delete(void* p, std::size_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t) noexcept { release(p); }
void operator delete(void* p, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { release(p); }
