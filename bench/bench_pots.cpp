// The pot planner on the shipped pot problems (problems/pots/) and on generated ones
// (planner::known_pot_problems): how many are solved, the plan time (median and 95th
// percentile, wall clock and the plan's CPU time) and the simulations spent, with the
// aim solved as a 1-D root (the default) and, with --compare, searched blindly like
// the other coordinates (PlannerOptions::solve_pot_aim = false), the two alternating
// problem by problem so that the machine's noise falls on both alike. With --pockets
// every problem is planned (aim solved) twice, alternately: with the standard capture
// circles and with the snooker preset's jawed pockets.
//
//   build/bench/bench_pots [--generated N (100)] [--seed S (1)] [--compare] [--pockets]
//                          [--problems DIR]
//
// It searches with the impact table (loaded from the cache, or built there on the first
// run) and verifies with the exact method, as `cueplan solve` does. Last, untimed: the
// share of cushion and jaw contacts (every ball's) the table answers when the plans'
// answers and alternatives are simulated as the search simulates them; the rest go to
// the exact method.
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <filesystem>
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

struct Tally {
  int solved = 0, runs = 0, unreachable = 0;
  std::vector<double> wall, cpu, evaluations, p_both, p_pot;
  void add(const planner::PlanResult& r, double cpu_s) {
    ++runs;
    solved += r.status == planner::PlanStatus::solved;
    unreachable += r.status == planner::PlanStatus::unreachable;
    wall.push_back(r.time_s);
    cpu.push_back(cpu_s);
    evaluations.push_back(r.evaluations);
    if (r.status == planner::PlanStatus::solved) {
      p_both.push_back(r.best.success.both.p);
      if (r.best.success.pot) p_pot.push_back(r.best.success.pot->p);
    }
  }
  std::string row(const std::string& label) const {
    double mean_both = 0.0, mean_pot = 0.0;
    for (double p : p_both) mean_both += p;
    for (double p : p_pot) mean_pot += p;
    if (!p_both.empty()) mean_both /= static_cast<double>(p_both.size());
    if (!p_pot.empty()) mean_pot /= static_cast<double>(p_pot.size());
    return fmt::format(
        "| {} | {}/{} ({:.1f} %) | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.0f} | {:.2f} | {:.2f} |",
        label, solved, runs, 100.0 * solved / std::max(1, runs), 1e3 * percentile(wall, 0.5),
        1e3 * percentile(wall, 0.95), 1e3 * percentile(cpu, 0.5), 1e3 * percentile(cpu, 0.95),
        percentile(evaluations, 0.5), mean_pot, mean_both);
  }
};

}  // namespace

int main(int argc, char** argv) {
  int generated = 100;
  uint64_t seed = 1;
  bool compare = false;
  bool pockets = false;
  std::string dir = std::string(CUEPLAN_PROBLEMS_DIR) + "/pots";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--generated") generated = std::atoi(next().c_str());
    else if (a == "--seed") seed = std::strtoull(next().c_str(), nullptr, 10);
    else if (a == "--compare") compare = true;
    else if (a == "--pockets") pockets = true;
    else if (a == "--problems") dir = next();
    else {
      fmt::print(stderr, "bench_pots: unknown argument {}\n", a);
      return 2;
    }
  }
  const physics::Scene snooker = physics::snooker_scene();
  std::string note;
  const physics::ImpactTable table = cli::load_or_build_table(
      snooker.ball_and_cushion, physics::ImpactTableOptions{}, cli::default_table_cache_dir(), &note);
  physics::SimulationOptions sim;
  sim.impact_method = physics::ImpactMethod::table;
  sim.table = &table;
  sim.impact_accuracy = 5e-6;  // as `cueplan solve` searches with the table

  std::vector<std::pair<std::string, problems::Problem>> cases;
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".yaml") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  for (const std::string& f : files) {
    const problems::LoadResult r = problems::load_problem(f);
    if (!r.ok()) {
      fmt::print(stderr, "bench_pots: {}\n", r.error);
      return 2;
    }
    if (!table.covers(r.problem->scene.ball_and_cushion)) {
      fmt::print(stderr, "bench_pots: {} is not a snooker table; skipped\n", f);
      continue;
    }
    cases.emplace_back("shipped", *r.problem);
  }
  for (planner::KnownShotProblem& k : planner::known_pot_problems(generated, seed, sim))
    cases.emplace_back("generated", std::move(k.problem));

  if (pockets) {
    const physics::PocketPreset preset = *physics::pocket_preset("snooker");
    Tally circles[2], jaws[2];
    for (const auto& [set, problem] : cases) {
      const int k = set == "shipped" ? 0 : 1;
      for (bool jawed : {false, true}) {
        problems::Problem p = problem;
        p.scene.pockets =
            jawed ? physics::jawed_pockets(p.scene.length, p.scene.width, preset.corner,
                                           preset.middle)
                  : physics::standard_pockets(p.scene.length, p.scene.width,
                                              physics::kDefaultPocketRadius);
        planner::PlannerOptions options;
        options.simulation = sim;
        options.threads = 1;
        const double cpu0 = thread_cpu_s();
        const planner::PlanResult r = planner::plan(p, options);
        (jawed ? jaws : circles)[k].add(r, thread_cpu_s() - cpu0);
      }
    }
    fmt::print("impact table: {}\n", note);
    fmt::print("| set | solved | median ms | p95 ms | CPU median ms | CPU p95 ms | median simulations | mean P(pot) | mean P(both) |\n");
    fmt::print("|---|---|---|---|---|---|---|---|---|\n");
    fmt::print("{}\n{}\n{}\n{}\n", circles[0].row("shipped, capture circles"),
               jaws[0].row("shipped, jawed pockets"), circles[1].row("generated, capture circles"),
               jaws[1].row("generated, jawed pockets"));
    return 0;
  }

  Tally shipped, known, shipped_blind, known_blind;
  // Contacts the table answered, and all contacts, of the plans' strokes (aim solved).
  int64_t table_contacts[2] = {0, 0}, contacts[2] = {0, 0};
  for (const auto& [set, problem] : cases) {
    for (bool solve_aim : {true, false}) {
      if (!solve_aim && !compare) continue;
      planner::PlannerOptions options;
      options.simulation = sim;
      options.threads = 1;
      options.solve_pot_aim = solve_aim;
      const double cpu0 = thread_cpu_s();
      const planner::PlanResult r = planner::plan(problem, options);
      const double cpu = thread_cpu_s() - cpu0;
      Tally& t = set == "shipped" ? (solve_aim ? shipped : shipped_blind)
                                  : (solve_aim ? known : known_blind);
      t.add(r, cpu);
      if (solve_aim && r.status == planner::PlanStatus::solved) {
        const int k = set == "shipped" ? 0 : 1;
        std::vector<physics::Shot> strokes{r.best.shot};
        for (const planner::PlannedShot& a : r.alternatives) strokes.push_back(a.shot);
        for (const physics::Shot& shot : strokes) {
          const physics::ShotResult s =
              physics::simulate(problem.scene, problem.cue_ball, shot, sim);
          table_contacts[k] += s.table_impacts;
          for (const physics::BallOutcome& b : s.balls) contacts[k] += b.cushion_hits + b.jaw_hits;
        }
      }
      if (r.status != planner::PlanStatus::solved)
        fmt::print(stderr, "{} {}{}: {}\n", set, problem.name, solve_aim ? "" : " (blind aim)",
                   r.message);
    }
  }
  fmt::print("impact table: {}\n", note);
  fmt::print("| set | solved | median ms | p95 ms | CPU median ms | CPU p95 ms | median simulations | mean P(pot) | mean P(both) |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|\n");
  fmt::print("{}\n{}\n", shipped.row("shipped, aim solved"), known.row("generated, aim solved"));
  if (compare)
    fmt::print("{}\n{}\n", shipped_blind.row("shipped, aim searched"),
               known_blind.row("generated, aim searched"));
  for (int k = 0; k < 2; ++k)
    fmt::print("{}: the table answers {} of {} cushion and jaw contacts ({:.1f} %) of the "
               "plans' answers and alternatives\n",
               k == 0 ? "shipped" : "generated", table_contacts[k], contacts[k],
               100.0 * static_cast<double>(table_contacts[k]) /
                   static_cast<double>(std::max<int64_t>(1, contacts[k])));
  return 0;
}
