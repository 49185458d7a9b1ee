// SPDX-License-Identifier: GPL-3.0-or-later
//! \file parallel.h
//! The one parallel policy of the library (TBB behind a small interface).
//! Results must never depend on the number of threads: callers write into
//! per-index slots and combine them in index order.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>

namespace subfab {

//! Calls fn(i) for every i in [begin, end), in parallel when the range is
//! larger than serial_threshold. fn must be safe to call concurrently for
//! different i. Exceptions thrown by fn are rethrown (the first one) after
//! the loop. Nested calls are safe under a lock or a once-flag: the thread
//! that waits for a loop runs only that loop's tasks (TBB task isolation).
void parallel_for(std::size_t begin, std::size_t end, const std::function<void(std::size_t)>& fn,
                  std::size_t serial_threshold = 1);

//! Limits the number of worker threads while the object lives
//! (0 = TBB's default: all cores). Create one in main(), not in the library.
class ThreadLimit {
 public:
  explicit ThreadLimit(std::size_t num_threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

//! Number of threads parallel_for may use now.
std::size_t max_threads();

}  // namespace subfab
