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

// Every arena block starts with a 16-byte header holding its size class;
// freed blocks go to their class's free list (LIFO) and are handed out again
// by later allocations of the same class. The free lists are per arena and
// per thread, so the addresses still follow from the computation alone
// (its sequence of allocations and frees), while the memory in use stays
// near the computation's live peak: a bump allocator alone grew to 10 GB
// inside one exact boolean of the tolerance measure (max planck, session 28),
// every temporary of CGAL's lazy kernel kept until the arena ended.
constexpr std::size_t kHeader = 16;
constexpr std::uint32_t kNoReuse = 0xffffffffu;  // over-aligned blocks: never reused
constexpr std::size_t kSmallStep = 16;           // classes 0..31: 16, 32, ..., 512 bytes
constexpr std::uint32_t kNumSmall = 32;
constexpr std::uint32_t kNumClasses = kNumSmall + 40;  // then powers of two: 1 KiB .. 2^49 bytes

std::uint32_t size_class(std::size_t n) {
  if (n <= kNumSmall * kSmallStep) return static_cast<std::uint32_t>((n + kSmallStep - 1) / kSmallStep) - 1;
  std::uint32_t c = kNumSmall;
  for (std::size_t size = std::size_t{1} << 10; size < n; size <<= 1) ++c;
  return c;
}

std::size_t class_size(std::uint32_t c) {
  return c < kNumSmall ? (c + 1) * kSmallStep : std::size_t{1} << (10 + (c - kNumSmall));
}

struct ArenaState {
  char* base = nullptr;
  char* top = nullptr;
  char* end = nullptr;
  bool allocating = false;
  bool reuse = true;
  ArenaState* previous = nullptr;
  void* free_list[kNumClasses] = {};  // per class: freed blocks (user pointers), linked through their first word
};

thread_local ArenaState* t_arena = nullptr;

ArenaState* owner(const void* p) {
  for (ArenaState* a = t_arena; a; a = a->previous)
    if (p >= a->base && p < a->end) return a;
  return nullptr;
}

void* arena_allocate(ArenaState* a, std::size_t n, std::size_t align) {
  if (n == 0) n = 1;
  const bool small_align = align <= kHeader;
  const std::uint32_t c = small_align && a->reuse && n <= class_size(kNumClasses - 1) ? size_class(n) : kNoReuse;
  if (c != kNoReuse) {
    if (void* p = a->free_list[c]) {
      a->free_list[c] = *static_cast<void**>(p);
      return p;
    }
    n = class_size(c);
  }
  if (align < kHeader) align = kHeader;
  auto user = reinterpret_cast<std::uintptr_t>(a->top) + kHeader;
  user = (user + align - 1) & ~(static_cast<std::uintptr_t>(align) - 1);
  if (user + n > reinterpret_cast<std::uintptr_t>(a->end)) throw std::bad_alloc();
  a->top = reinterpret_cast<char*>(user + n);
  *reinterpret_cast<std::uint32_t*>(user - kHeader) = c;
  return reinterpret_cast<void*>(user);
}

void arena_release(ArenaState* a, void* p) noexcept {
  const std::uint32_t c = *reinterpret_cast<const std::uint32_t*>(static_cast<char*>(p) - kHeader);
  if (c == kNoReuse) return;
  *static_cast<void**>(p) = a->free_list[c];
  a->free_list[c] = p;
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
  if (!p) return;
  if (ArenaState* a = owner(p)) {
    arena_release(a, p);
    return;
  }
  std::free(p);
}

}  // namespace

DeterministicArena::DeterministicArena(std::size_t reserve_bytes, bool reuse_freed) : state_(nullptr) {
  void* base = mmap(nullptr, reserve_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (base == MAP_FAILED) return;
  void* raw = std::malloc(sizeof(ArenaState));
  if (!raw) {
    munmap(base, reserve_bytes);
    return;
  }
  auto* a = new (raw) ArenaState;
  a->reuse = reuse_freed;
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
