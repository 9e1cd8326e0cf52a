// Time of one step's series from the `exact` method's two fast kernels alone (both
// contacts slipping, in tau or in sigma; physics/src/impact_taylor_series.hpp), at
// order 16 (tolerance 1e-12), through the dispatch the single path uses
// (fast_series: AVX2 where the CPU has it, else SSE2).
//
//   bench_taylor_kernels --benchmark_repetitions=3
//
// States: the first state of each of bench_impact's 4096 uniform inputs (same seed and
// ranges), in the kernels' slip variables. Each call's state depends on the last
// call's highest coefficient (times zero), so consecutive steps do not overlap: the
// time is a step's latency, as in an impact, where a step starts from the last one's end.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "cueplan/physics/cushion_impact.hpp"
#include "impact_taylor.hpp"

namespace {

using namespace cueplan::physics;
using namespace cueplan::physics::detail::taylor;

struct State {
  double q[kState];
};

std::vector<State> uniform_states(const CushionParams& params) {
  std::mt19937_64 rng(2010);
  std::uniform_real_distribution<double> alpha(0.01, 179.99), k(-3.0, 3.0), v(0.01, 5.0);
  const detail::Geometry g = detail::Geometry::from(params);
  std::vector<State> out;
  for (int i = 0; i < 4096; ++i) {
    const double speed = v(rng), a = alpha(rng), kt = k(rng), ks = k(rng);
    const BallState in = incoming_state_k(speed, a, kt, ks, params.radius);
    const double scale = std::hypot(in.velocity.x, in.velocity.y), o = params.radius / scale;
    const detail::Scaled sc{in.velocity.x / scale, in.velocity.y / scale, in.spin.x * o,
                            in.spin.y * o, in.spin.z * o};
    const detail::Slips sl = detail::slips_of(g, sc);
    if (std::hypot(sl.ix, sl.iy) == 0.0 || std::hypot(sl.cx, sl.cy) == 0.0) continue;
    out.push_back({{sl.ix, sl.iy, sl.cx, sl.cy, sc.oz, 0.0, 0.0}});
  }
  return out;
}

void BM_TaylorKernel(benchmark::State& state) {
  const CushionParams params;
  const Constants constants = Constants::from(detail::Geometry::from(params));
  const std::vector<State> states = uniform_states(params);
  const Kernel kernel = state.range(0) == 0 ? Kernel::tau : Kernel::sigma;
  const int order = static_cast<int>(state.range(1));
  Coefficients<double> s{};
  double carry = 0.0;
  size_t i = 0;
  for (auto _ : state) {
    for (int c = 0; c < kState; ++c) s.c[c][0] = states[i].q[c];
    s.c[kXI][0] += carry;
    fast_series(kernel, constants, order, s);
    carry = 0.0 * s.c[kXI][order + 1];
    if (++i == states.size()) i = 0;
  }
  benchmark::DoNotOptimize(carry);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TaylorKernel)->ArgNames({"sigma", "order"})->ArgsProduct({{0, 1}, {4, 8, 12, 16, 20, 24}});

}  // namespace

BENCHMARK_MAIN();
