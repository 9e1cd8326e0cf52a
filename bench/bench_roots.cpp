// The event solver's root finder (physics/src/polynomial_roots.hpp) against plain
// bisection to rounding, the method it replaced, on cushion-like event polynomials: a
// ball's distance to a cushion line c0 + c1 t + c2 t^2 (c0 in (-3, 0) m, a small share
// a nanometre from the line; the approach speed c1 up to 5 m/s; rolling (0.1 m/s^2) or
// sliding (2 m/s^2) friction in c2), on [0, the piece's end or the turning point].
// Counters: `differ`, the share of roots that are not bit for bit bisection's (both are
// roots to rounding: a sign change between neighbouring doubles, or an exact zero), and
// `worst_relative`, the largest |difference| / root.
//
// BM_Length: the simulator's vector length (cueplan/physics/vec2.hpp, the root of the sum
// of squares) against std::hypot, on 4096 velocity-like vectors: `chain`, each length
// feeding the next input (the latency the event loop sees), and `independent` (the
// throughput).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "cueplan/physics/vec2.hpp"
#include "polynomial_roots.hpp"

namespace {

using cueplan::physics::detail::evaluate;

struct Quadratic {
  double c[3];
  double lo, hi, f_lo, f_hi;
};

std::vector<Quadratic> cushion_quadratics(size_t n) {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Quadratic> out;
  while (out.size() < n) {
    Quadratic q;
    const bool rolling = unit(rng) < 0.6;
    const double distance = 3.0 * unit(rng) * (unit(rng) < 0.02 ? 1e-9 : 1.0);
    const double speed = 5.0 * unit(rng) * unit(rng) + 1e-3;
    const double decel = rolling ? 0.1 : 2.0;
    const double cosine = std::abs(2.0 * unit(rng) - 1.0);
    q.c[0] = -distance;
    q.c[1] = speed * cosine;
    q.c[2] = -0.5 * decel * (rolling ? cosine : 2.0 * unit(rng) - 1.0);
    q.lo = 0.0;
    q.hi = rolling ? speed / decel : speed / decel * 2.0 / 7.0;
    const double turn = -q.c[1] / (2.0 * q.c[2]);
    if (turn > q.lo && turn < q.hi) q.hi = turn;
    q.f_lo = evaluate(q.c, 2, q.lo);
    q.f_hi = evaluate(q.c, 2, q.hi);
    if (q.f_lo == 0.0 || q.f_hi == 0.0 || (q.f_lo < 0.0) == (q.f_hi < 0.0)) continue;
    out.push_back(q);
  }
  return out;
}

// The replaced method: halving the bracket until its midpoint rounds to an end.
double bisection(const double* c, double a, double b, double fa) {
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (a + b);
    if (m <= a || m >= b) break;
    const double fm = evaluate(c, 2, m);
    if (fm == 0.0) return m;
    if ((fm < 0.0) == (fa < 0.0)) {
      a = m;
      fa = fm;
    } else {
      b = m;
    }
  }
  return 0.5 * (a + b);
}

double newton(const Quadratic& q) {
  return cueplan::physics::detail::bracketed_root(q.c, 2, q.lo, q.hi, q.f_lo, q.f_hi);
}

void BM_EventRoot(benchmark::State& state, bool use_newton) {
  const std::vector<Quadratic> qs = cushion_quadratics(1 << 16);
  size_t i = 0;
  for (auto _ : state) {
    const Quadratic& q = qs[i++ & (qs.size() - 1)];
    double r = use_newton ? newton(q) : bisection(q.c, q.lo, q.hi, q.f_lo);
    benchmark::DoNotOptimize(r);
  }
  size_t differ = 0;
  double worst = 0.0;
  for (const Quadratic& q : qs) {
    const double a = newton(q), b = bisection(q.c, q.lo, q.hi, q.f_lo);
    differ += std::memcmp(&a, &b, sizeof a) != 0;
    worst = std::max(worst, std::abs(a - b) / b);
  }
  state.counters["differ"] = static_cast<double>(differ) / static_cast<double>(qs.size());
  state.counters["worst_relative"] = worst;
}

BENCHMARK_CAPTURE(BM_EventRoot, bisection, false);
BENCHMARK_CAPTURE(BM_EventRoot, newton, true);

// hypot: true for std::hypot, false for vec2::length; chain: each result feeds the next.
void BM_Length(benchmark::State& state, bool hypot, bool chain) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> component(-5.0, 5.0);
  std::vector<double> xs(4096), ys(4096);
  for (size_t i = 0; i < xs.size(); ++i) {
    xs[i] = component(rng);
    ys[i] = component(rng);
  }
  const auto length = [hypot](double x, double y) {
    return hypot ? std::hypot(x, y) : cueplan::physics::vec2::length(x, y);
  };
  double carry = 0.0;
  for (auto _ : state) {
    double sum = 0.0;
    for (size_t i = 0; i < xs.size(); ++i) {
      const double l = length(xs[i], ys[i] + carry);
      sum += l;
      if (chain) carry = 1e-300 * l;  // a dependence, not a change of the inputs
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(xs.size()));
}
BENCHMARK_CAPTURE(BM_Length, hypot_chain, true, true);
BENCHMARK_CAPTURE(BM_Length, length_chain, false, true);
BENCHMARK_CAPTURE(BM_Length, hypot_independent, true, false);
BENCHMARK_CAPTURE(BM_Length, length_independent, false, false);

}  // namespace

BENCHMARK_MAIN();
