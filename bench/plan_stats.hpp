// What the plan benchmarks (bench_planner, bench_pots) measure their distributions with.
#pragma once

#include <algorithm>
#include <ctime>
#include <vector>

namespace cueplan::bench {

// The q-quantile (0..1) of `v`, linear between order statistics; 0 for none.
inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const size_t i = static_cast<size_t>(pos);
  const double f = pos - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}

// CPU time of the calling thread (s): on a machine shared with other work, the steadier
// measure of what a plan costs.
inline double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace cueplan::bench
