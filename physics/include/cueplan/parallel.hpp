// One way to spread independent work over threads, shared by every layer (the impact
// table's build, the planner's polishes and spin maps, the command line's batches).
//
// Each item writes only its own result slot, so results come out in input order and
// identical for any thread count. No pool outlives the call and nothing is shared
// between calls: safe from many threads at once.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <thread>
#include <vector>

namespace cueplan {

// Threads to use when `requested` are asked for: that many, or one per core for 0 or less.
inline unsigned thread_count(int requested) {
  return requested > 0 ? static_cast<unsigned>(requested)
                       : std::max(1u, std::thread::hardware_concurrency());
}

// The same for `items` work items: at least 1, at most `items`.
inline unsigned thread_count(int requested, size_t items) {
  return static_cast<unsigned>(std::max<size_t>(1, std::min<size_t>(thread_count(requested), items)));
}

// Calls work(i, worker) once for every i in [0, items), from `threads` threads (this
// one included); `worker` in [0, threads) names the thread, for per-thread scratch.
template <typename Work>
void parallel_for(size_t items, unsigned threads, const Work& work) {
  threads = std::max(1u, static_cast<unsigned>(std::min<size_t>(threads, std::max<size_t>(items, 1))));
  if (threads == 1) {
    for (size_t i = 0; i < items; ++i) work(i, 0u);
    return;
  }
  std::atomic<size_t> next{0};
  const auto drain = [&](unsigned worker) {
    for (size_t i = next++; i < items; i = next++) work(i, worker);
  };
  std::vector<std::jthread> pool;
  pool.reserve(threads - 1);
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(drain, t);
  drain(0);
}

// The same, telling `progress(done)` on this thread how many items have finished: after
// each item this thread works on, then every `interval` while the other threads finish
// the last items, and once with done == items at the end.
template <typename Work, typename Progress>
void parallel_for(size_t items, unsigned threads, const Work& work, const Progress& progress,
                  std::chrono::milliseconds interval = std::chrono::milliseconds(50)) {
  threads = std::max(1u, static_cast<unsigned>(std::min<size_t>(threads, std::max<size_t>(items, 1))));
  std::atomic<size_t> next{0};
  std::atomic<size_t> done{0};
  const auto drain = [&](unsigned worker) {
    for (size_t i = next++; i < items; i = next++) {
      work(i, worker);
      const size_t finished = ++done;
      if (worker == 0) progress(finished);
    }
  };
  {
    std::vector<std::jthread> pool;
    pool.reserve(threads - 1);
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(drain, t);
    drain(0);
    while (done.load() < items) {
      std::this_thread::sleep_for(interval);
      progress(done.load());
    }
  }  // joins the workers
  progress(items);
}

}  // namespace cueplan
