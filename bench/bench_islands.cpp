// Obstacle fields: the NLopt global stages against the OMPL one (KPIECE1 over strokes,
// spread by landing position) on problems whose feasible strokes are split into small
// islands by obstacle balls (planner::obstacle_field_problems). For every method and
// total evaluation budget: the success rate over problems x seeds, and the median and
// 95th-percentile plan time. First it describes the scenes: the fraction of a uniform
// sample of strokes that ends on a ball (or in a pocket), and the number of open aim
// windows - runs of aims at the witness's speed and spin that come to rest - in a
// scan of the whole turn.
//
// A plain program (a distribution over problems, as bench_planner). It searches with
// the snooker impact table (from the cache, or built there once) and verifies with the
// exact method, as the planner does by default; no success probabilities are estimated.
//
//   build/bench/bench_islands            # 50 problems, 12 obstacles, seeds 1..3
//
// Options: --problems N (50), --obstacles N (12), --seeds N (3), --budgets A,B,C
// (400,1000,2000), --methods M,N,... (crs2,direct_l,mlsl,ompl_kpiece1), --threads N (1).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cueplan/physics/impact_table.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/route.hpp"
#include "cueplan/api/table_cache.hpp"

namespace {

using namespace cueplan;

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t i = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5));
  return v[i];
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

bool ends_on_ball_or_pocket(const physics::ShotResult& r) {
  return r.status == physics::ShotStatus::hit_obstacle || r.status == physics::ShotStatus::pocketed;
}

}  // namespace

int main(int argc, char** argv) {
  int count = 50, obstacles = 12, seeds = 3, threads = 1;
  std::vector<int> budgets = {400, 1000, 2000};
  std::vector<std::string> methods = {"crs2", "direct_l", "mlsl", "ompl_kpiece1"};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_islands: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--problems") count = std::atoi(value().c_str());
    else if (a == "--obstacles") obstacles = std::atoi(value().c_str());
    else if (a == "--seeds") seeds = std::atoi(value().c_str());
    else if (a == "--threads") threads = std::atoi(value().c_str());
    else if (a == "--budgets") {
      budgets.clear();
      for (const std::string& b : split(value())) budgets.push_back(std::atoi(b.c_str()));
    } else if (a == "--methods") methods = split(value());
    else {
      std::fprintf(stderr, "bench_islands: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  planner::quiet_ompl_messages();
  std::string note;
  const physics::ImpactTable table = cli::load_or_build_table(
      physics::snooker_scene().ball_and_cushion, physics::ImpactTableOptions{},
      cli::default_table_cache_dir(), &note);
  std::fprintf(stderr, "impact table: %s\n", note.c_str());
  physics::SimulationOptions sim;
  sim.impact_method = physics::ImpactMethod::table;
  sim.table = &table;
  sim.impact_accuracy = 1e-5;  // the table's measured accuracy class
  sim.record_path = false;

  const auto problems = planner::obstacle_field_problems(count, obstacles, 2026, sim);

  // The scenes: blocked fraction of a uniform stroke sample, open aim windows.
  std::vector<double> blocked_fraction, windows;
  std::mt19937_64 rng(7);
  auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
  };
  for (const auto& k : problems) {
    const problems::Problem& p = k.problem;
    constexpr int kSample = 2000;
    int blocked = 0;
    for (int i = 0; i < kSample; ++i) {
      physics::Shot s;
      s.speed = uniform(p.limits.speed_min, p.limits.speed_max);
      s.aim_deg = uniform(-180.0, 180.0);
      const double r = p.limits.spin_max * std::sqrt(uniform(0.0, 1.0)), t = uniform(-M_PI, M_PI);
      s.topspin_k = r * std::sin(t);
      s.sidespin_k = r * std::cos(t);
      if (ends_on_ball_or_pocket(physics::simulate(p.scene, p.cue_ball, s, sim))) ++blocked;
    }
    blocked_fraction.push_back(static_cast<double>(blocked) / kSample);
    constexpr int kAims = 3600;  // 0.1 deg apart
    int open_runs = 0;
    bool first_open = false, previous = false;
    for (int i = 0; i < kAims; ++i) {
      physics::Shot s = k.shot;
      s.aim_deg = -180.0 + 360.0 * i / kAims;
      const bool open = physics::simulate(p.scene, p.cue_ball, s, sim).status == physics::ShotStatus::rest;
      if (i == 0) first_open = open;
      if (open && !previous) ++open_runs;
      previous = open;
    }
    if (first_open && previous && open_runs > 1) --open_runs;  // the run across +-180 deg
    windows.push_back(open_runs);
  }
  std::printf("%zu problems, %d obstacles each, seeds 1..%d\n", problems.size(), obstacles, seeds);
  std::printf("uniform strokes ending on a ball or in a pocket: median %.0f %% (5th-95th %.0f-%.0f %%)\n",
              100 * percentile(blocked_fraction, 0.5), 100 * percentile(blocked_fraction, 0.05),
              100 * percentile(blocked_fraction, 0.95));
  std::printf("open aim windows at the witness's speed and spin: median %.0f (5th-95th %.0f-%.0f)\n",
              percentile(windows, 0.5), percentile(windows, 0.05), percentile(windows, 0.95));

  std::printf("\n| global | budget | solved | median time (s) | p95 time (s) | median evaluations | families solved per problem (median) |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
  for (int budget : budgets) {
    for (const std::string& name : methods) {
      planner::PlannerOptions o;
      if (!planner::parse_global_method(name, &o.global)) {
        std::fprintf(stderr, "bench_islands: unknown method %s\n", name.c_str());
        return 2;
      }
      o.max_evaluations = budget;
      o.robustness_samples = 0;
      o.threads = threads;
      o.max_time_s = 60.0;
      o.simulation = sim;
      int solved = 0, runs = 0;
      std::vector<double> times, evaluations, families;
      for (const auto& k : problems) {
        std::set<std::string> solved_families;
        for (int seed = 1; seed <= seeds; ++seed) {
          o.seed = static_cast<uint64_t>(seed);
          const planner::PlanResult r = planner::plan(k.problem, o);
          ++runs;
          times.push_back(r.time_s);
          evaluations.push_back(r.evaluations);
          if (r.status != planner::PlanStatus::solved) continue;
          ++solved;
          solved_families.insert(r.best.family);
          for (const auto& a : r.alternatives) solved_families.insert(a.family);
        }
        families.push_back(static_cast<double>(solved_families.size()));
      }
      std::printf("| %s | %d | %d / %d (%.0f %%) | %.3f | %.3f | %.0f | %.0f |\n", name.c_str(), budget,
                  solved, runs, 100.0 * solved / runs, percentile(times, 0.5), percentile(times, 0.95),
                  percentile(evaluations, 0.5), percentile(families, 0.5));
      std::fflush(stdout);
    }
  }
  return 0;
}
