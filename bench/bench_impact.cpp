// Time per cushion impact for every method, with each configuration's error against a
// converged reference on the same inputs, so run time and error come from one run.
//
//   bench_impact --benchmark_format=json > impact.json
//   python3 bench/error_vs_time.py impact.json   # table and plot for bench/README.md
//
// Inputs: 4096 impacts drawn uniformly (seeded) over the domain of the accuracy
// targets: alpha in (0, 180) deg, |k_T|, |k_S| <= 3, V0 in (0.01, 5) m/s. References:
// both exact methods at tolerance 1e-14; each exact method's errors are measured
// against the other one's reference (the two agree to about 1e-13), every other
// method's against the extrapolation method's, as before it had a second.
//
// Google Benchmark's time per impact is the mean over the inputs (the loop cycles
// through them); every configuration also reports the median of the inputs' times
// measured one by one (`median_ns`, wall-clock: a median shrugs off the preemptions of
// a shared machine, a mean of single timings would not), and the batch rows the time
// per impact of resolve_impacts over all 4096 inputs at each SIMD lane width. The anchor of the
// ratios is `paper` with N = 5000: the project's own implementation of the paper's
// fixed-step scheme (physics/src/impact_paper.cpp), built with the same flags.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "cueplan/physics/cushion_impact.hpp"
#include "cueplan/physics/impact_table.hpp"
#include "cueplan/api/table_cache.hpp"

namespace {

using namespace cueplan::physics;

struct Sample {
  double speed, alpha_deg, topspin_k, sidespin_k;
  BallState state;
  ImpactResult reference_taylor;         // exact at 1e-14
  ImpactResult reference_extrapolation;  // extrapolation at 1e-14
};

ImpactResult converged(const CushionParams& p, const BallState& in, ImpactMethod method) {
  ImpactOptions o;
  o.method = method;
  o.tolerance = 1e-14;
  o.max_steps = 1000000;
  return resolve_impact(p, in, o);
}

// 4096 seeded samples; rolling = true fixes k_T = 1 (natural roll, the commonest
// state at a cushion).
std::vector<Sample> make_samples(bool rolling) {
  CushionParams params;
  std::mt19937_64 rng(rolling ? 1963 : 2010);
  std::uniform_real_distribution<double> alpha(0.01, 179.99), k(-3.0, 3.0), v(0.01, 5.0);
  std::vector<Sample> out;
  for (int i = 0; i < 4096; ++i) {
    Sample s{v(rng), alpha(rng), k(rng), k(rng), {}, {}, {}};
    if (rolling) s.topspin_k = 1.0;
    s.state = incoming_state_k(s.speed, s.alpha_deg, s.topspin_k, s.sidespin_k, params.radius);
    s.reference_taylor = converged(params, s.state, ImpactMethod::exact);
    s.reference_extrapolation = converged(params, s.state, ImpactMethod::extrapolation);
    out.push_back(s);
  }
  return out;
}

const std::vector<Sample>& samples() {
  static const std::vector<Sample> all = make_samples(false);
  return all;
}

const std::vector<Sample>& rolling_samples() {
  static const std::vector<Sample> all = make_samples(true);
  return all;
}

const ImpactTable& table() {
  static const ImpactTable t = cueplan::cli::load_or_build_table(
      CushionParams{}, ImpactTableOptions{}, cueplan::cli::default_table_cache_dir());
  return t;
}

// The reference for a method: the other exact method's, converged.
const ImpactResult& reference_for(ImpactMethod method, const Sample& s) {
  return method == ImpactMethod::extrapolation ? s.reference_taylor : s.reference_extrapolation;
}

// Error of one result against the reference: outgoing velocity and R * spin over V0.
double state_error(const CushionParams& p, const ImpactResult& r, const ImpactResult& ref,
                   double v0) {
  const Vec3 dv = r.outgoing.velocity - ref.outgoing.velocity;
  const Vec3 dw = r.outgoing.spin - ref.outgoing.spin;
  return std::max({std::abs(dv.x), std::abs(dv.y), p.radius * std::abs(dw.x),
                   p.radius * std::abs(dw.y), p.radius * std::abs(dw.z)}) /
         v0;
}

// Errors of a configuration over every sample, as counters.
void count_errors(benchmark::State& state, const ImpactOptions& options,
                  const std::vector<Sample>& in) {
  const CushionParams params;
  std::vector<double> errors;
  double worst_speed = 0.0, worst_angle = 0.0;
  long long evaluations = 0;
  for (const Sample& s : in) {
    const ImpactResult r = resolve_impact(params, s.state, options);
    const ImpactResult& ref = reference_for(options.method, s);
    errors.push_back(state_error(params, r, ref, s.speed));
    worst_speed = std::max(worst_speed, std::abs(r.rebound_speed - ref.rebound_speed) / s.speed);
    worst_angle = std::max(worst_angle, std::abs(r.rebound_angle_deg - ref.rebound_angle_deg));
    evaluations += r.rhs_evaluations;
  }
  std::sort(errors.begin(), errors.end());
  state.counters["max_state_err"] = errors.back();
  state.counters["median_state_err"] = errors[errors.size() / 2];
  state.counters["max_speed_err"] = worst_speed;
  state.counters["max_angle_err_deg"] = worst_angle;
  state.counters["rhs_per_impact"] =
      static_cast<double>(evaluations) / static_cast<double>(in.size());
}

// The median of the inputs' times one by one (after one warm-up pass), in ns.
void count_median_time(benchmark::State& state, const ImpactOptions& options,
                       const std::vector<Sample>& in) {
  const CushionParams params;
  std::vector<double> ns;
  for (int pass = 0; pass < 2; ++pass) {
    ns.clear();
    for (const Sample& s : in) {
      const auto t0 = std::chrono::steady_clock::now();
      const ImpactResult r = resolve_impact(params, s.state, options);
      const auto t1 = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(r.rebound_speed);
      ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count());
    }
  }
  std::nth_element(ns.begin(), ns.begin() + ns.size() / 2, ns.end());
  state.counters["median_ns"] = ns[ns.size() / 2];
}

void run_impacts(benchmark::State& state, ImpactOptions options,
                 const std::vector<Sample>& in = samples()) {
  const CushionParams params;
  count_errors(state, options, in);
  size_t i = 0;
  for (auto _ : state) {
    const ImpactResult r = resolve_impact(params, in[i].state, options);
    benchmark::DoNotOptimize(r.rebound_speed);
    if (++i == in.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
  // (Outside the timed loop: the per-impact timer would disturb it.)
  count_median_time(state, options, in);
}

void BM_ImpactExact(benchmark::State& state) {
  ImpactOptions o;
  o.tolerance = std::pow(10.0, -static_cast<double>(state.range(0)));
  run_impacts(state, o);
}
BENCHMARK(BM_ImpactExact)->ArgName("tol_exp")->Arg(6)->Arg(8)->Arg(9)->Arg(10)->Arg(12)->Arg(13);

void BM_ImpactExtrapolation(benchmark::State& state) {
  ImpactOptions o;
  o.method = ImpactMethod::extrapolation;
  o.tolerance = std::pow(10.0, -static_cast<double>(state.range(0)));
  run_impacts(state, o);
}
BENCHMARK(BM_ImpactExtrapolation)
    ->ArgName("tol_exp")
    ->Arg(6)
    ->Arg(8)
    ->Arg(9)
    ->Arg(10)
    ->Arg(12)
    ->Arg(13);

void BM_ImpactPaper(benchmark::State& state) {
  ImpactOptions o;
  o.method = ImpactMethod::paper;
  o.paper_steps = static_cast<int>(state.range(0));
  run_impacts(state, o);
}
BENCHMARK(BM_ImpactPaper)->ArgName("N")->Arg(500)->Arg(5000)->Arg(50000);

// resolve_impacts over all the inputs at once, per SIMD lane width (0: the widest
// the CPU has; 1: the one-impact path in a loop). Every result is bit for bit the
// single path's, so the errors are the exact rows' at the default tolerance.
void BM_ImpactBatch(benchmark::State& state) {
  const CushionParams params;
  ImpactOptions o;
  o.batch_lanes = static_cast<int>(state.range(0));
  const std::vector<Sample>& in = samples();
  std::vector<BallState> incoming;
  for (const Sample& s : in) incoming.push_back(s.state);
  std::vector<ImpactResult> out(in.size());
  count_errors(state, o, in);
  for (auto _ : state) {
    resolve_impacts(params, incoming, out, o);
    benchmark::DoNotOptimize(out.back().rebound_speed);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(in.size()));
}
BENCHMARK(BM_ImpactBatch)->ArgName("lanes")->Arg(0)->Arg(1)->Arg(2)->Arg(4)->Arg(8)->UseRealTime();

void BM_ImpactTable(benchmark::State& state) {
  ImpactOptions o;
  o.method = ImpactMethod::table;
  o.table = &table();
  run_impacts(state, o);
}
BENCHMARK(BM_ImpactTable);

// The same with the impacts the table does not answer resolved at the exact method's
// default tolerance, 1e-12, instead of the one matched to the table.
void BM_ImpactTableStrictFallback(benchmark::State& state) {
  ImpactOptions o;
  o.method = ImpactMethod::table;
  o.table = &table();
  o.table_fallback_tolerance = ImpactOptions{}.tolerance;
  run_impacts(state, o);
}
BENCHMARK(BM_ImpactTableStrictFallback);

// Natural roll: the table's own query time (it answers 99.5 % of these) against
// the exact methods on the same inputs.
void BM_ImpactRollingTable(benchmark::State& state) {
  ImpactOptions o;
  o.method = ImpactMethod::table;
  o.table = &table();
  run_impacts(state, o, rolling_samples());
}
BENCHMARK(BM_ImpactRollingTable);

// The table's own query, ImpactTable::resolve, without resolve_impact's checks of
// the parameters and the state and without the exact fallback: the time per query
// over all samples (declined ones return at once), errors over the answered ones.
void run_table_queries(benchmark::State& state, const std::vector<Sample>& in) {
  const CushionParams params;
  const ImpactTable& t = table();
  std::vector<double> errors;
  double worst_speed = 0.0, worst_angle = 0.0;
  for (const Sample& s : in) {
    ImpactResult r;
    if (!t.resolve(params, s.state, &r)) continue;
    const ImpactResult& ref = s.reference_extrapolation;
    errors.push_back(state_error(params, r, ref, s.speed));
    worst_speed = std::max(worst_speed, std::abs(r.rebound_speed - ref.rebound_speed) / s.speed);
    worst_angle = std::max(worst_angle, std::abs(r.rebound_angle_deg - ref.rebound_angle_deg));
  }
  std::sort(errors.begin(), errors.end());

  size_t i = 0;
  ImpactResult r;
  for (auto _ : state) {
    benchmark::DoNotOptimize(t.resolve(params, in[i].state, &r));
    benchmark::DoNotOptimize(r.rebound_speed);
    if (++i == in.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["answered"] = static_cast<double>(errors.size()) / static_cast<double>(in.size());
  state.counters["max_state_err"] = errors.back();
  state.counters["median_state_err"] = errors[errors.size() / 2];
  state.counters["max_speed_err"] = worst_speed;
  state.counters["max_angle_err_deg"] = worst_angle;
  state.counters["rhs_per_impact"] = 0.0;
}

void BM_TableQuery(benchmark::State& state) { run_table_queries(state, samples()); }
BENCHMARK(BM_TableQuery);

void BM_TableQueryRolling(benchmark::State& state) { run_table_queries(state, rolling_samples()); }
BENCHMARK(BM_TableQueryRolling);

void BM_ImpactRollingExact(benchmark::State& state) {
  run_impacts(state, ImpactOptions{}, rolling_samples());
}
BENCHMARK(BM_ImpactRollingExact);

void BM_ImpactRollingExtrapolation(benchmark::State& state) {
  ImpactOptions o;
  o.method = ImpactMethod::extrapolation;
  run_impacts(state, o, rolling_samples());
}
BENCHMARK(BM_ImpactRollingExtrapolation);

}  // namespace

BENCHMARK_MAIN();
