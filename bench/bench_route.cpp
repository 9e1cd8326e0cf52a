// Multi-stroke routes (planner::plan_route) on the shipped route problems: for every
// planner (SST, RRT, KPIECE1) and control sampler (directed, random), the share of
// seeds that find a route within the problem's time budget and the time to the first
// route (median and worst over the seeds that found one).
//
// A plain program rather than a Google Benchmark one, like bench_planner: what it
// measures is a distribution over seeds (success and time to a first route), not the
// mean of one repeated call. Every run stops at its first route (stop_at_first_solution)
// so that SST's time is comparable with RRT's and KPIECE1's. A second table compares
// SST's route success probability at its first route with that after the whole budget.
//
//   build/bench/bench_route                      # 10 seeds, markdown table on stdout
//   build/bench/bench_route --seeds 20 --time 2  # other seed count or budget (s)
//
// Options: --problems DIR (default: the source tree's problems/routes/), --seeds N (10),
// --time S (default: each problem's time_budget_s).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "cueplan/planner/route.hpp"
#include "cueplan/problems/problem.hpp"

#ifndef CUEPLAN_PROBLEMS_DIR
#define CUEPLAN_PROBLEMS_DIR "problems"
#endif

namespace {

using namespace cueplan;

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return -1.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir = std::string(CUEPLAN_PROBLEMS_DIR) + "/routes";
  int seeds = 10;
  double time_s = 0.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--problems" && has_value) dir = argv[++i];
    else if (a == "--seeds" && has_value) seeds = std::atoi(argv[++i]);
    else if (a == "--time" && has_value) time_s = std::atof(argv[++i]);
    else {
      std::fprintf(stderr, "bench_route: unknown argument '%s'\n", a.c_str());
      return 2;
    }
  }
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".yaml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  planner::quiet_ompl_messages();

  std::printf("| problem | planner | sampler | routes found | time to first route, median (s) | "
              "worst (s) | strokes | route success, median |\n|---|---|---|---|---|---|---|---|\n");
  for (const auto& file : files) {
    const problems::LoadResult loaded = problems::load_problem(file.string());
    if (!loaded.ok()) {
      std::fprintf(stderr, "%s\n", loaded.error.c_str());
      return 2;
    }
    const problems::Problem& p = *loaded.problem;
    for (planner::RoutePlanner pl :
         {planner::RoutePlanner::sst, planner::RoutePlanner::rrt, planner::RoutePlanner::kpiece1})
      for (planner::RouteSampler sa : {planner::RouteSampler::directed, planner::RouteSampler::random}) {
        planner::RouteOptions o;
        o.planner = pl;
        o.sampler = sa;
        o.max_strokes = p.max_strokes.value_or(3);
        o.max_time_s = time_s > 0.0 ? time_s : p.time_budget_s.value_or(5.0);
        o.stop_at_first_solution = true;
        o.robustness_samples = 100;
        int found = 0;
        std::vector<double> first, success;
        std::vector<double> strokes;
        for (int s = 1; s <= seeds; ++s) {
          o.seed = static_cast<uint64_t>(s);
          const planner::RouteResult r = planner::plan_route(p, o);
          if (r.status != planner::RouteStatus::solved) continue;
          ++found;
          first.push_back(r.time_to_first_solution_s);
          success.push_back(r.route_success_probability);
          strokes.push_back(static_cast<double>(r.strokes.size()));
        }
        const auto cell = [](double v, const char* pattern) {
          char buf[32];
          if (v < 0.0) return std::string("-");
          std::snprintf(buf, sizeof buf, pattern, v);
          return std::string(buf);
        };
        std::printf("| %s | %s | %s | %d / %d | %s | %s | %s | %s |\n",
                    file.stem().string().c_str(), planner::to_string(pl), planner::to_string(sa),
                    found, seeds, cell(quantile(first, 0.5), "%.3f").c_str(),
                    cell(quantile(first, 1.0), "%.3f").c_str(),
                    cell(quantile(strokes, 0.5), "%.0f").c_str(),
                    cell(success.empty() ? -1.0 : quantile(success, 0.5), "%.2f").c_str());
        std::fflush(stdout);
      }
  }

  // SST is anytime: with the whole budget it trades the first route for one of lower
  // summed risk. Its route success against the first route's, same seeds.
  std::printf("\n| problem | SST directed | route success at the first route, median | "
              "with the whole budget, median | whole-budget runs that improved it |\n"
              "|---|---|---|---|---|\n");
  for (const auto& file : files) {
    const problems::Problem p = *problems::load_problem(file.string()).problem;
    planner::RouteOptions o;
    o.max_strokes = p.max_strokes.value_or(3);
    o.max_time_s = time_s > 0.0 ? time_s : p.time_budget_s.value_or(5.0);
    o.robustness_samples = 100;
    std::vector<double> first, whole;
    int improved = 0;
    for (int s = 1; s <= seeds; ++s) {
      o.seed = static_cast<uint64_t>(s);
      o.stop_at_first_solution = true;
      const planner::RouteResult a = planner::plan_route(p, o);
      o.stop_at_first_solution = false;
      const planner::RouteResult b = planner::plan_route(p, o);
      const double pa = a.status == planner::RouteStatus::solved ? a.route_success_probability : 0.0;
      const double pb = b.status == planner::RouteStatus::solved ? b.route_success_probability : 0.0;
      first.push_back(pa);
      whole.push_back(pb);
      improved += pb > pa ? 1 : 0;
    }
    std::printf("| %s | %.3g s budget | %.3f | %.3f | %d / %d |\n", file.stem().string().c_str(),
                o.max_time_s, quantile(first, 0.5), quantile(whole, 0.5), improved, seeds);
    std::fflush(stdout);
  }
  return 0;
}
