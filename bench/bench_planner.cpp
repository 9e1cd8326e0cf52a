// The planner on the shipped problems and on generated ones: success rate, plan time
// (median, 95th percentile) and plans per second for every pairing of a global and a
// local NLopt method, and the success rate of one pairing against a time budget.
//
// A plain program rather than a Google Benchmark one: what it measures is a
// distribution over problems (success and time percentiles), not the mean of one
// repeated call. It searches with an impact table covering each problem's ball and
// cushion (loaded from the cache, or built there on the first run, about 30 s per
// parameter set: snooker, pool and carom here) and verifies the answers with the
// exact method, as the planner does by default with a table.
//
//   build/bench/bench_planner --out planner.json     # all pairings, then the budget sweep
//   python3 bench/planner_plot.py planner.json --svg bench/planner_success_vs_budget.svg
//
// Options: --problems DIR (default: the source tree's problems/), --generated N (50),
// --seeds N (plans per problem with seeds 1..N, 2), --global M / --local M (those
// pairings only; "none" skips them), --tight-evaluations N (the second pairing table's
// budget, 400; 0 skips it), --sweep-global M / --sweep-local M (the methods the time sweep is
// centred on; default: PlannerOptions' defaults), --no-sweep, --out FILE (JSON),
// --per-run (every plan's status, time, CPU time, evaluations and answer P in the JSON too); and
// to try other settings: --max-evaluations N, --global-share F, --local-starts N,
// --samples N, --stop-at-first-solution.
//
// Besides success and time, each row reports what the answers are worth to a player:
// the mean success probability of the answer (solved plans) judged on fresh noise
// draws the planner never saw (seed + 1000003, 400 strokes), the same for the
// generated problems' known strokes (the witnesses), and how often the answer
// succeeds at least as often as the witness.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <deque>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "cueplan/physics/impact_table.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/problems/problem.hpp"
#include "plan_stats.hpp"
#include "cueplan/api/table_cache.hpp"

#ifndef CUEPLAN_PROBLEMS_DIR
#define CUEPLAN_PROBLEMS_DIR "problems"
#endif

namespace {

using namespace cueplan;
using bench::percentile;
using bench::thread_cpu_s;

struct Case {
  std::string set;  // "shipped" or "generated"
  problems::Problem problem;
  physics::SimulationOptions simulation;  // with a table covering the problem
  std::optional<physics::Shot> witness;   // generated: the stroke the target came from
};

struct Run {
  std::string set, name;
  uint64_t seed = 0;
  bool solved = false;
  std::string status;
  double time_s = 0.0;
  double cpu_s = 0.0;  // the plan's thread's CPU time (plans run on one thread here)
  int evaluations = 0;
  int families = 0;
  double miss = 0.0;
  double answer_p = -1.0;   // the answer's success probability on fresh draws (solved plans)
  double witness_p = -1.0;  // the witness's, on the same fresh draws (generated problems)
};

struct Summary {
  std::string global, local, label;
  double budget_s = 0.0;  // sweep rows only
  std::vector<Run> runs;
  int max_evaluations = 0;
};

struct Stats {
  double success = 0.0, shipped = 0.0, generated = 0.0, median_ms = 0.0, p95_ms = 0.0,
         plans_per_s = 0.0, mean_evaluations = 0.0, mean_families = 0.0, cpu_median_ms = 0.0,
         cpu_p95_ms = 0.0;
  int no_solution = 0, exhausted = 0;
  // The answers' success probabilities (solved plans), and on generated problems the
  // fraction whose answer succeeds at least as often as the witness.
  double mean_answer_p = 0.0, mean_witness_p = 0.0, at_least_witness = 0.0;
};

Stats stats(const std::vector<Run>& runs) {
  Stats s;
  std::vector<double> times, cpu;
  int n_ship = 0, n_gen = 0, ok_ship = 0, ok_gen = 0;
  double total = 0.0;
  for (const Run& r : runs) {
    times.push_back(r.time_s);
    cpu.push_back(r.cpu_s);
    total += r.time_s;
    s.mean_evaluations += r.evaluations;
    s.mean_families += r.families;
    if (r.set == "shipped") {
      ++n_ship;
      ok_ship += r.solved;
    } else {
      ++n_gen;
      ok_gen += r.solved;
    }
    s.no_solution += r.status == "no_solution_found";
    s.exhausted += r.status == "budget_exhausted";
  }
  int answered = 0, compared = 0;
  for (const Run& r : runs) {
    if (r.answer_p < 0.0) continue;
    ++answered;
    s.mean_answer_p += r.answer_p;
    if (r.witness_p < 0.0) continue;
    ++compared;
    s.mean_witness_p += r.witness_p;
    s.at_least_witness += r.answer_p >= r.witness_p;
  }
  if (answered) s.mean_answer_p /= answered;
  if (compared) {
    s.mean_witness_p /= compared;
    s.at_least_witness /= compared;
  }
  const double n = static_cast<double>(runs.size());
  s.success = (ok_ship + ok_gen) / n;
  s.shipped = n_ship ? static_cast<double>(ok_ship) / n_ship : 0.0;
  s.generated = n_gen ? static_cast<double>(ok_gen) / n_gen : 0.0;
  s.median_ms = 1e3 * percentile(times, 0.5);
  s.p95_ms = 1e3 * percentile(times, 0.95);
  s.cpu_median_ms = 1e3 * percentile(cpu, 0.5);
  s.cpu_p95_ms = 1e3 * percentile(cpu, 0.95);
  s.plans_per_s = n / total;
  s.mean_evaluations /= n;
  s.mean_families /= n;
  return s;
}

constexpr uint64_t kFreshSeed = 1000003;  // added to the plan's seed
constexpr int kFreshSamples = 400;

std::vector<Run> run_all(const std::vector<Case>& cases, planner::PlannerOptions options,
                         int seeds) {
  std::vector<Run> runs;
  for (const Case& c : cases)
    for (int seed = 1; seed <= seeds; ++seed) {
      options.seed = static_cast<uint64_t>(seed);
      options.simulation = c.simulation;
      const double cpu0 = thread_cpu_s();
      const planner::PlanResult r = planner::plan(c.problem, options);
      const double cpu1 = thread_cpu_s();
      Run run;
      run.cpu_s = cpu1 - cpu0;
      run.set = c.set;
      run.name = c.problem.name;
      run.seed = options.seed;
      run.solved = r.status == planner::PlanStatus::solved;
      run.status = planner::to_string(r.status);
      run.time_s = r.time_s;
      run.evaluations = r.evaluations;
      run.families = run.solved ? 1 + static_cast<int>(r.alternatives.size()) : 0;
      run.miss = r.best.miss_distance;
      // The answer's success judged afresh: on draws the planner never saw (another
      // seed), so that picking the best of several noisy estimates does not flatter it.
      if (run.solved && options.robustness_samples > 0) {
        const uint64_t fresh = options.seed + kFreshSeed;
        run.answer_p = planner::success_probability(c.problem, r.best.shot, options.noise,
                                                    kFreshSamples, fresh, options.simulation);
        if (c.witness)
          run.witness_p = planner::success_probability(c.problem, *c.witness, options.noise,
                                                       kFreshSamples, fresh, options.simulation);
      }
      runs.push_back(run);
    }
  return runs;
}

std::string json_summary(const Summary& s, bool per_run) {
  const Stats t = stats(s.runs);
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "{\"global\": \"%s\", \"local\": \"%s\", \"label\": \"%s\", \"budget_s\": %.6g, "
                "\"max_evaluations\": %d, "
                "\"plans\": %zu, \"success\": %.6g, \"success_shipped\": %.6g, "
                "\"success_generated\": %.6g, \"median_ms\": %.6g, \"p95_ms\": %.6g, "
                "\"plans_per_s\": %.6g, \"mean_evaluations\": %.6g, \"mean_families\": %.6g, "
                "\"no_solution_found\": %d, \"budget_exhausted\": %d, \"mean_answer_p\": %.6g, "
                "\"mean_witness_p\": %.6g, \"at_least_witness\": %.6g, \"cpu_median_ms\": %.6g, "
                "\"cpu_p95_ms\": %.6g",
                s.global.c_str(), s.local.c_str(), s.label.c_str(), s.budget_s, s.max_evaluations,
                s.runs.size(),
                t.success, t.shipped, t.generated, t.median_ms, t.p95_ms, t.plans_per_s,
                t.mean_evaluations, t.mean_families, t.no_solution, t.exhausted, t.mean_answer_p,
                t.mean_witness_p, t.at_least_witness, t.cpu_median_ms, t.cpu_p95_ms);
  std::string out = buf;
  if (!per_run) return out + "}";
  out += ", \"runs\": [";
  for (size_t i = 0; i < s.runs.size(); ++i) {
    const Run& r = s.runs[i];
    std::snprintf(buf, sizeof buf,
                  "%s{\"set\": \"%s\", \"problem\": \"%s\", \"seed\": %llu, \"status\": \"%s\", "
                  "\"time_ms\": %.4g, \"cpu_ms\": %.4g, \"evaluations\": %d, \"families\": %d, "
                  "\"answer_p\": %.4g, \"witness_p\": %.4g}",
                  i ? ", " : "", r.set.c_str(), r.name.c_str(),
                  static_cast<unsigned long long>(r.seed), r.status.c_str(), 1e3 * r.time_s,
                  1e3 * r.cpu_s, r.evaluations, r.families, r.answer_p, r.witness_p);
    out += buf;
  }
  return out + "]}";
}

void print_row(const Summary& s) {
  const Stats t = stats(s.runs);
  std::printf("| %s | %s | %.1f %% | %.0f %% | %.1f %% | %.2f ms | %.2f ms | %.0f | %.0f | %.1f | %d | %d "
              "| %.1f %% | %.1f %% | %.0f %% | %.2f ms | %.2f ms |\n",
              s.global.c_str(), s.local.c_str(), 100 * t.success, 100 * t.shipped,
              100 * t.generated, t.median_ms, t.p95_ms, t.plans_per_s, t.mean_evaluations,
              t.mean_families, t.no_solution, t.exhausted, 100 * t.mean_answer_p,
              100 * t.mean_witness_p, 100 * t.at_least_witness, t.cpu_median_ms, t.cpu_p95_ms);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::string problems_dir = CUEPLAN_PROBLEMS_DIR, out_path, only_global, only_local;
  int generated = 50, seeds = 2, tight_evaluations = 400;
  bool sweep = true, per_run = false;
  int base_evaluations = -1, base_starts = -1, base_samples = -1;
  bool first_solution = false;
  double base_share = -1.0;
  planner::PlannerOptions defaults;
  planner::GlobalMethod sweep_global = defaults.global;
  planner::LocalMethod sweep_local = defaults.local;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_planner: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--problems") problems_dir = value();
    else if (a == "--generated") generated = std::atoi(value().c_str());
    else if (a == "--seeds") seeds = std::max(1, std::atoi(value().c_str()));
    else if (a == "--global") only_global = value();
    else if (a == "--local") only_local = value();
    else if (a == "--sweep-global") planner::parse_global_method(value(), &sweep_global);
    else if (a == "--sweep-local") planner::parse_local_method(value(), &sweep_local);
    else if (a == "--no-sweep") sweep = false;
    else if (a == "--tight-evaluations") tight_evaluations = std::atoi(value().c_str());
    else if (a == "--max-evaluations") base_evaluations = std::atoi(value().c_str());
    else if (a == "--global-share") base_share = std::atof(value().c_str());
    else if (a == "--local-starts") base_starts = std::atoi(value().c_str());
    else if (a == "--samples") base_samples = std::atoi(value().c_str());
    else if (a == "--stop-at-first-solution") first_solution = true;
    else if (a == "--out") out_path = value();
    else if (a == "--per-run") per_run = true;
    else {
      std::fprintf(stderr, "bench_planner: unknown argument %s\n", a.c_str());
      return 2;
    }
  }

  // The problems, each with an impact table covering its ball and cushion (tables
  // are loaded from the cache, or built there once).
  std::vector<Case> cases;
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(problems_dir))
    if (e.path().extension() == ".yaml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    problems::LoadResult r = problems::load_problem(f.string());
    if (!r.ok()) {
      std::fprintf(stderr, "bench_planner: %s\n", r.error.c_str());
      return 2;
    }
    cases.push_back({"shipped", std::move(*r.problem), {}, std::nullopt});
  }
  std::deque<physics::ImpactTable> tables;
  auto simulation_for = [&](const physics::CushionParams& params) {
    auto it = std::find_if(tables.begin(), tables.end(),
                           [&](const physics::ImpactTable& t) { return t.covers(params); });
    if (it == tables.end()) {
      std::string note;
      const auto t0 = std::chrono::steady_clock::now();
      tables.push_back(cli::load_or_build_table(
          params, physics::ImpactTableOptions{}, cli::default_table_cache_dir(), &note));
      std::fprintf(stderr, "impact table: %s (%.1f s)\n", note.c_str(),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      it = std::prev(tables.end());
    }
    physics::SimulationOptions sim;
    sim.impact_method = physics::ImpactMethod::table;
    sim.table = &*it;
    sim.impact_accuracy = 1e-5;  // the table's measured accuracy class
    sim.record_path = false;
    return sim;
  };
  for (Case& c : cases) c.simulation = simulation_for(c.problem.scene.ball_and_cushion);
  const physics::SimulationOptions snooker = simulation_for(physics::snooker_scene().ball_and_cushion);
  for (auto& k : planner::known_shot_problems(generated, 2026, snooker))
    cases.push_back({"generated", std::move(k.problem), snooker, k.shot});
  std::fprintf(stderr, "%zu shipped and %d generated problems, %d seeds each\n", files.size(),
               generated, seeds);

  planner::PlannerOptions base;
  if (base_evaluations > 0) base.max_evaluations = base_evaluations;
  if (base_share > 0) base.global_share = base_share;
  if (base_starts > 0) base.local_starts = base_starts;
  if (base_samples >= 0) base.robustness_samples = base_samples;
  base.stop_at_first_solution = first_solution;
  if (physics::Validation e = base.validate()) {
    std::fprintf(stderr, "bench_planner: %s\n", e->message().c_str());
    return 2;
  }
  // Warm up: page the table in and settle the clocks.
  for (size_t i = 0; i < std::min<size_t>(cases.size(), 5); ++i) {
    planner::PlannerOptions o = base;
    o.simulation = cases[i].simulation;
    planner::plan(cases[i].problem, o);
  }

  // Every pairing at the default evaluation budget, and again at a tight one, where
  // the methods differ more.
  const planner::GlobalMethod globals[] = {planner::GlobalMethod::direct_l, planner::GlobalMethod::crs2,
                                           planner::GlobalMethod::mlsl, planner::GlobalMethod::isres};
  const planner::LocalMethod locals[] = {planner::LocalMethod::bobyqa, planner::LocalMethod::sbplx,
                                         planner::LocalMethod::cobyla, planner::LocalMethod::neldermead};
  std::vector<Summary> pairings, budgets;
  std::vector<int> pairing_budgets{base.max_evaluations};
  if (tight_evaluations > 0) pairing_budgets.push_back(tight_evaluations);
  for (int budget : pairing_budgets) {
    std::printf("\nevery pairing, max_evaluations %d\n\n"
                "| global | local | success | shipped | generated | median | p95 | plans/s | "
                "mean evaluations | mean families (solved) | no solution found | budget exhausted | "
                "answer P | witness P | answer >= witness | CPU median | CPU p95 |\n"
                "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
                budget);
    for (auto g : globals)
      for (auto l : locals) {
        if (!only_global.empty() && only_global != planner::to_string(g)) continue;
        if (!only_local.empty() && only_local != planner::to_string(l)) continue;
        planner::PlannerOptions o = base;
        o.global = g;
        o.local = l;
        o.max_evaluations = budget;
        Summary s{planner::to_string(g), planner::to_string(l),
                  budget == base.max_evaluations ? "default budget" : "tight budget", 0.0,
                  run_all(cases, o, seeds)};
        s.max_evaluations = budget;
        print_row(s);
        pairings.push_back(std::move(s));
      }
  }

  // Success against the search's time budget (evaluations unbounded): the default
  // local method under every global one, and the default global one with every local.
  if (sweep) {
    std::vector<std::pair<planner::GlobalMethod, planner::LocalMethod>> curves;
    for (auto g : globals) curves.push_back({g, sweep_local});
    for (auto l : locals)
      if (l != sweep_local) curves.push_back({sweep_global, l});
    std::printf("\nsuccess against time budget (evaluations unbounded)\n\n"
                "| global | local | budget | success | shipped | generated | median | p95 |\n"
                "|---|---|---:|---:|---:|---:|---:|---:|\n");
    for (const auto& [g, l] : curves)
      for (double budget_ms : {0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0}) {
        planner::PlannerOptions o = base;
        o.global = g;
        o.local = l;
        o.max_time_s = 1e-3 * budget_ms;
        o.max_evaluations = 1000000;
        Summary s{planner::to_string(g), planner::to_string(l), "time budget", 1e-3 * budget_ms,
                  run_all(cases, o, seeds)};
        const Stats t = stats(s.runs);
        std::printf("| %s | %s | %.2g ms | %.1f %% | %.0f %% | %.1f %% | %.2f ms | %.2f ms |\n",
                    s.global.c_str(), s.local.c_str(), budget_ms, 100 * t.success, 100 * t.shipped,
                    100 * t.generated, t.median_ms, t.p95_ms);
        std::fflush(stdout);
        budgets.push_back(std::move(s));
      }
  }

  if (!out_path.empty()) {
    std::ofstream out(out_path);
    out << "{\"machine_note\": \"see bench/README.md\", \"seeds\": " << seeds
        << ", \"generated\": " << generated << ", \"pairings\": [";
    for (size_t i = 0; i < pairings.size(); ++i) out << (i ? ",\n" : "\n") << json_summary(pairings[i], per_run);
    out << "],\n\"budgets\": [";
    for (size_t i = 0; i < budgets.size(); ++i) out << (i ? ",\n" : "\n") << json_summary(budgets[i], per_run);
    out << "]}\n";
  }
  return 0;
}
