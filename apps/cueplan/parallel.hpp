// Spreads independent work items over threads; each item writes only its own slot,
// so results come out in input order and identical for any thread count.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace cueplan::cli {

// Threads to use for `requested` (0: one per core) and `items` work items.
inline unsigned thread_count(int requested, size_t items) {
  unsigned n = requested > 0 ? static_cast<unsigned>(requested)
                             : std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(std::max<size_t>(1, std::min<size_t>(n, items)));
}

// Calls work(i) once for every i in [0, items), from `threads` threads.
template <typename Work>
void parallel_for(size_t items, unsigned threads, const Work& work) {
  if (threads <= 1) {
    for (size_t i = 0; i < items; ++i) work(i);
    return;
  }
  std::atomic<size_t> next{0};
  const auto drain = [&] {
    for (size_t i = next++; i < items; i = next++) work(i);
  };
  std::vector<std::jthread> pool;
  pool.reserve(threads - 1);
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(drain);
  drain();
}

}  // namespace cueplan::cli
