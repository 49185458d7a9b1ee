// SPDX-License-Identifier: GPL-3.0-or-later
#include "subfab/core/parallel.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <exception>
#include <mutex>

namespace subfab {

void parallel_for(std::size_t begin, std::size_t end, const std::function<void(std::size_t)>& fn,
                  std::size_t serial_threshold) {
  if (end <= begin) return;
  if (end - begin <= serial_threshold || max_threads() <= 1) {
    for (std::size_t i = begin; i < end; ++i) fn(i);
    return;
  }
  std::exception_ptr first_error;
  std::size_t first_index = end;
  std::mutex mutex;
  // Isolated: a thread waiting for this loop to finish runs only this
  // loop's tasks, never an outer loop's. Without it a loop nested under a
  // once-flag or a lock (a block's index built on first use by whichever
  // task asks first: lazy_solid.h) could have its thread take an outer
  // task that waits for that same flag: a deadlock.
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_for(begin, end, [&](std::size_t i) {
      try {
        fn(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        // Keep the error of the smallest index, so the reported error does
        // not depend on scheduling.
        if (i < first_index) {
          first_index = i;
          first_error = std::current_exception();
        }
      }
    });
  });
  if (first_error) std::rethrow_exception(first_error);
}

struct ThreadLimit::Impl {
  std::unique_ptr<tbb::global_control> control;
};

ThreadLimit::ThreadLimit(std::size_t num_threads) : impl_(std::make_unique<Impl>()) {
  if (num_threads > 0) {
    impl_->control = std::make_unique<tbb::global_control>(
        tbb::global_control::max_allowed_parallelism, num_threads);
  }
}

ThreadLimit::~ThreadLimit() = default;

std::size_t max_threads() {
  return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
}

}  // namespace subfab
