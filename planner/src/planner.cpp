// plan(): global search, local polish per family, verification, robustness.
//
// Stages, in order:
//   1. global   - NLopt's global method over the unit cube of strokes, remembering the
//                 best stroke of every family (route and spin) it meets;
//   2. polish   - the local method from the best stroke of each of the best families,
//                 in parallel, each start on its own seeded stream; while nothing is
//                 solved and the budget allows, polishes still improving are continued
//                 and, once all have converged, the next families are started;
//   3. verify   - with the impact table, the polished strokes are simulated again
//                 with the exact method (and polished with it if they moved out);
//   4. rank     - one shot per family, solved first, by success probability;
//   5. robust   - (--robust) each solved shot polished for its success probability;
//   6. report   - status and a sentence a coach can read.
#include <nlopt.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "cueplan/planner/planner.hpp"
#include "nlopt_stage.hpp"
#include "ompl_stage.hpp"
#include "outcome.hpp"
#include "robustness.hpp"
#include "search_space.hpp"

namespace cueplan::planner {
namespace {

using Clock = std::chrono::steady_clock;
using detail::FamilyKey;
using detail::SearchSpace;
using detail::StageSettings;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPolishStop = 0.1;       // a polish stops at a miss of 10 % of the tolerance
constexpr double kPolishStep = 0.01;      // first step of a polish, unit-cube coordinates
constexpr double kXTolerance = 1e-5;      // unit-cube coordinates
constexpr double kFTolerance = 2e-5;      // m
constexpr int kMinPolishEvaluations = 100;  // a new polish needs this much budget
constexpr int kMinContinueEvaluations = 40;  // and a continued one this much
constexpr int kVerifyEvaluations = 200;
// A polish that ran out of evaluations counts as converged when it has stalled: over
// the last half of its evaluations (at least kStallEvaluations) its best score fell by
// no more than kProgress (m), or so slowly that kHorizon times as many evaluations
// again would not bring it down to the target.
constexpr double kProgress = 1e-4;
constexpr int kStallEvaluations = 30;
constexpr double kHorizon = 4.0;   // exact re-polish of a shot the table misjudged
constexpr double kExactAccuracy = 1e-9;   // exact verification (the simulator's default)
// Streams of the seed: 0 the global stage, 1 + i the i-th polish, then the rest.
constexpr uint64_t kVerifyStream = 1u << 20;
constexpr uint64_t kRobustStream = 1u << 21;

std::string format(const char* pattern, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, pattern, args...);
  return buf;
}

std::string mm(double metres) {
  if (!std::isfinite(metres)) return "no rest position";
  return metres < 0.1 ? format("%.1f mm", 1e3 * metres) : format("%.3g m", metres);
}

// A stroke and its nominal score.
struct Candidate {
  physics::Shot shot;
  double score = kInf;
};

// The nominal objective: simulate the stroke at u, score it, count it, and (in the
// global stage) remember the best stroke of each family.
class NominalObjective {
 public:
  NominalObjective(const problems::Problem& problem, const SearchSpace& space,
                   const physics::SimulationOptions& simulation, bool enforce_rigid_limit,
                   bool record_families)
      : problem_(problem), space_(space), simulation_(simulation),
        enforce_rigid_limit_(enforce_rigid_limit), record_families_(record_families) {}

  double operator()(const double* u) {
    const physics::Shot shot = space_.shot(u);
    const physics::ShotResult r =
        physics::simulate(problem_.scene, problem_.cue_ball, shot, simulation_);
    ++evaluations_;
    const double f = detail::shot_score(problem_, r, enforce_rigid_limit_);
    last_ = {f, r.final_position, r.status == physics::ShotStatus::rest};
    if (f < best_.score) best_ = {shot, f};
    best_history_.push_back(best_.score);
    if (record_families_) {
      auto [it, inserted] = families_.try_emplace(detail::family_key(shot, r));
      if (f < it->second.score) it->second = {shot, f};
    }
    return f;
  }

  int evaluations() const { return evaluations_; }
  const Candidate& best() const { return best_; }
  // The stroke last scored: its score and where it stopped.
  const detail::Landing& last() const { return last_; }
  // True when the best score has stopped falling toward `target` (see kHorizon).
  bool stalled(double target) const {
    const size_t n = best_history_.size();
    if (n < 2 * static_cast<size_t>(kStallEvaluations)) return false;
    const double fall = best_history_[n / 2 - 1] - best_.score;  // over the last half
    return fall <= kProgress || kHorizon * fall < best_.score - target;
  }
  const std::map<FamilyKey, Candidate>& families() const { return families_; }

 private:
  const problems::Problem& problem_;
  const SearchSpace& space_;
  const physics::SimulationOptions& simulation_;
  bool enforce_rigid_limit_;
  bool record_families_;
  int evaluations_ = 0;
  std::vector<double> best_history_;  // best score after each evaluation
  Candidate best_;
  detail::Landing last_;
  std::map<FamilyKey, Candidate> families_;
};

// The robust objective: 1 - the soft success over common noise draws, plus a
// penalty that keeps the nominal stroke inside the landing zone.
class RobustObjective {
 public:
  RobustObjective(const problems::Problem& problem, const SearchSpace& space,
                  const physics::SimulationOptions& simulation, const PlannerOptions& options,
                  const std::vector<detail::NoiseDraw>& draws)
      : problem_(problem), space_(space), simulation_(simulation), options_(options),
        draws_(draws) {}

  double operator()(const double* u) {
    const physics::Shot shot = space_.shot(u);
    const physics::ShotResult r =
        physics::simulate(problem_.scene, problem_.cue_ball, shot, simulation_);
    ++simulations_;
    const double nominal = detail::shot_score(problem_, r, options_.enforce_rigid_limit);
    const double tol = problem_.tolerance;
    const double outside = std::max(0.0, nominal - 0.8 * tol) / tol;
    const double f = 1.0 - detail::soft_success(problem_, shot, draws_, options_.noise,
                                                simulation_, &simulations_) +
                     outside;
    if (f < best_score_) {
      best_score_ = f;
      best_ = shot;
    }
    return f;
  }

  int simulations() const { return simulations_; }
  const physics::Shot& best() const { return best_; }

 private:
  const problems::Problem& problem_;
  const SearchSpace& space_;
  const physics::SimulationOptions& simulation_;
  const PlannerOptions& options_;
  const std::vector<detail::NoiseDraw>& draws_;
  int simulations_ = 0;
  double best_score_ = kInf;
  physics::Shot best_;
};

// One local polish and how it ended.
struct Polish {
  Candidate best;
  nlopt_result code = NLOPT_FAILURE;
  int evaluations = 0;
  bool stalled = false;  // see NominalObjective::stalled

  // Ended on its own tolerances, or stopped making progress before its budget ended.
  bool converged() const { return detail::converged(code) || stalled; }
};

Polish polish(const problems::Problem& problem, const PlannerOptions& options,
              const physics::SimulationOptions& simulation, const physics::Shot& start,
              int max_evaluations, double max_time_s, uint64_t stream) {
  // Centre a free aim on the start, so the polish never meets the seam at +-180.
  const SearchSpace space(problem.limits, start.aim_deg);
  NominalObjective objective(problem, space, simulation, options.enforce_rigid_limit, false);
  std::vector<double> x = space.point(start);
  StageSettings s;
  s.algorithm = detail::nlopt_local(options.local);
  s.max_evaluations = std::max(1, max_evaluations);
  s.max_time_s = max_time_s;
  s.stop_value = kPolishStop * problem.tolerance;
  s.x_tolerance = kXTolerance;
  s.f_tolerance = kFTolerance;
  s.initial_step = kPolishStep;
  nlopt_srand(detail::stream_seed(options.seed, stream));
  Polish p;
  p.code = detail::run_stage(s, &x, &objective);
  p.best = objective.best();
  p.evaluations = objective.evaluations();
  p.stalled = objective.stalled(problem.tolerance);
  if (p.evaluations == 0) p.best = {start, kInf};
  return p;
}

// Runs task(0 .. count-1) on up to `threads` threads; each task writes only its own slot.
template <class Task>
void run_parallel(int count, int threads, const Task& task) {
  threads = std::min(threads, count);
  if (threads <= 1) {
    for (int i = 0; i < count; ++i) task(i);
    return;
  }
  std::atomic<int> next{0};
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      for (int i = next++; i < count; i = next++) task(i);
    });
  for (std::thread& t : pool) t.join();
}

std::string check_problem(const problems::Problem& p) {
  if (std::string why = p.scene.validate(); !why.empty()) return "problem: " + why;
  if (std::string why = p.scene.check_position(p.cue_ball, "cue_ball"); !why.empty())
    return "problem: " + why;
  if (std::string why = p.scene.check_position(p.target, "target"); !why.empty())
    return "problem: " + why;
  if (!std::isfinite(p.tolerance) || !(p.tolerance > 0.0))
    return format("problem: tolerance must be positive (m), got %.10g", p.tolerance);
  const problems::Limits& l = p.limits;
  if (!std::isfinite(l.speed_min) || !(l.speed_min > 0.0))
    return format("problem: limits.speed_min must be positive (m/s), got %.10g", l.speed_min);
  if (!std::isfinite(l.speed_max) || !(l.speed_max > l.speed_min))
    return format("problem: limits.speed_max must exceed speed_min (m/s), got %.10g", l.speed_max);
  if (!std::isfinite(l.spin_max) || !(l.spin_max > 0.0))
    return format("problem: limits.spin_max must be positive, got %.10g", l.spin_max);
  if (l.cushions_min < 0 || l.cushions_max < l.cushions_min)
    return format("problem: limits.cushions must satisfy 0 <= min <= max, got [%d, %d]",
                  l.cushions_min, l.cushions_max);
  const problems::AimLimit& a = l.aim;
  if (!std::isfinite(a.lo_deg) || !std::isfinite(a.hi_deg))
    return "problem: limits.aim must be finite";
  if (a.mode == problems::AimMode::range && !(a.lo_deg < a.hi_deg && a.hi_deg <= a.lo_deg + 360.0))
    return format("problem: limits.aim range must satisfy lo < hi <= lo + 360 deg, got [%.10g, %.10g]",
                  a.lo_deg, a.hi_deg);
  return {};
}

// A described shot with its nominal score, for ranking.
struct Final {
  PlannedShot shot;
  double score = kInf;
};

bool better(const Final& a, const Final& b) {
  if (a.shot.solves != b.shot.solves) return a.shot.solves;
  if (a.shot.solves && a.shot.success_probability != b.shot.success_probability)
    return a.shot.success_probability > b.shot.success_probability;
  if (a.score != b.score) return a.score < b.score;
  return a.shot.miss_distance < b.shot.miss_distance;
}

}  // namespace

std::string PlannerOptions::validate() const {
  auto bad = [](const char* field, const char* rule, double value) {
    return format("%s %s, got %.10g", field, rule, value);
  };
  if (global != GlobalMethod::direct_l && global != GlobalMethod::crs2 &&
      global != GlobalMethod::mlsl && global != GlobalMethod::isres &&
      global != GlobalMethod::ompl_kpiece1)
    return bad("global", "must be direct_l, crs2, mlsl, isres or ompl_kpiece1", static_cast<int>(global));
  if (local != LocalMethod::bobyqa && local != LocalMethod::sbplx &&
      local != LocalMethod::cobyla && local != LocalMethod::neldermead)
    return bad("local", "must be bobyqa, sbplx, cobyla or neldermead", static_cast<int>(local));
  if (max_evaluations < 10) return bad("max_evaluations", "must be at least 10", max_evaluations);
  if (!std::isfinite(max_time_s) || !(max_time_s > 0.0))
    return bad("max_time_s", "must be positive and finite (s)", max_time_s);
  if (local_starts < 1) return bad("local_starts", "must be at least 1", local_starts);
  if (!(global_share > 0.0 && global_share < 1.0))
    return bad("global_share", "must lie in (0, 1)", global_share);
  if (threads < 1) return bad("threads", "must be at least 1", threads);
  if (std::string why = noise.validate(); !why.empty()) return why;
  if (robustness_samples < 0)
    return bad("robustness_samples", "must not be negative", robustness_samples);
  if (robust_search_samples < 1)
    return bad("robust_search_samples", "must be at least 1", robust_search_samples);
  if (robust_max_evaluations < 0)
    return bad("robust_max_evaluations", "must not be negative", robust_max_evaluations);
  if (robust && robustness_samples < 1)
    return bad("robustness_samples", "must be at least 1 with robust", robustness_samples);
  if (max_alternatives < 0) return bad("max_alternatives", "must not be negative", max_alternatives);
  if (simulation.max_events < 1)
    return bad("simulation.max_events", "must be at least 1", simulation.max_events);
  if (!std::isfinite(simulation.impact_accuracy) || !(simulation.impact_accuracy > 0.0))
    return bad("simulation.impact_accuracy", "must be positive and finite",
               simulation.impact_accuracy);
  return {};
}

PlanResult plan(const problems::Problem& problem, const PlannerOptions& options) {
  const Clock::time_point started = Clock::now();
  const Clock::time_point deadline =
      started + std::chrono::duration_cast<Clock::duration>(
                    std::chrono::duration<double>(options.max_time_s));
  auto seconds_left = [&] { return std::chrono::duration<double>(deadline - Clock::now()).count(); };
  PlanResult result;
  auto finish = [&] {
    result.time_s = std::chrono::duration<double>(Clock::now() - started).count();
    return result;
  };
  if (std::string why = options.validate(); !why.empty()) {
    result.message = why;
    return finish();
  }
  if (std::string why = check_problem(problem); !why.empty()) {
    result.message = why;
    return finish();
  }
  const double tol = problem.tolerance;
  physics::SimulationOptions sim = options.simulation;
  sim.record_path = false;
  // The search's own copy cuts strokes that run on around the table short.
  physics::SimulationOptions search_sim = sim;
  search_sim.max_events = detail::search_event_cap(problem, sim.max_events);

  // 1. Global stage over the whole stroke space, remembering every family's best.
  const SearchSpace space(problem.limits);
  NominalObjective global(problem, space, search_sim, options.enforce_rigid_limit, true);
  if (options.global == GlobalMethod::ompl_kpiece1) {
    detail::LandingSearch s;
    s.dimension = space.dimension();
    s.aim_coordinate = problem.limits.aim.mode == problems::AimMode::free ? 1 : -1;
    s.max_evaluations = std::max(1, static_cast<int>(options.global_share * options.max_evaluations));
    s.max_time_s = std::max(1e-6, options.global_share * seconds_left());
    s.goal_score = tol;  // a stroke in the zone: the polish takes it from there
    s.table_length = problem.scene.length;
    s.table_width = problem.scene.width;
    s.seed = detail::stream_seed(options.seed, 0);
    detail::explore_landings(s, [&global](const double* u) {
      global(u);
      return global.last();
    });
  } else {
    std::vector<double> x(static_cast<size_t>(space.dimension()), 0.5);
    StageSettings s;
    s.algorithm = detail::nlopt_global(options.global);
    s.max_evaluations = std::max(1, static_cast<int>(options.global_share * options.max_evaluations));
    s.max_time_s = std::max(1e-6, options.global_share * seconds_left());
    s.inner = detail::nlopt_local(options.local);
    s.inner_max_evaluations = std::max(20, s.max_evaluations / 10);
    s.inner_x_tolerance = kXTolerance;
    s.inner_f_tolerance = kFTolerance;
    s.inner_step = kPolishStep;
    nlopt_srand(detail::stream_seed(options.seed, 0));
    detail::run_stage(s, &x, &global);
  }
  result.evaluations += global.evaluations();
  const bool global_timed_out = seconds_left() <= 0.0;

  // Families by their best score (map order breaks ties, so the ranking is fixed);
  // strokes that end early are starts only when nothing else was met.
  std::vector<Candidate> starts;
  for (bool ended_early : {false, true}) {
    for (const auto& [key, c] : global.families())
      if (key.ended_early == ended_early) starts.push_back(c);
    if (!starts.empty()) break;
  }
  std::stable_sort(starts.begin(), starts.end(),
                   [](const Candidate& a, const Candidate& b) { return a.score < b.score; });

  // 2. Local polish in passes of up to local_starts starts, while nothing is solved.
  std::vector<Polish> polished;
  bool timed_out = global_timed_out;
  // Each pass either continues the polishes that ran out of evaluations while still
  // improving (the best families first) or, when all have converged, starts the next
  // families; it ends once a shot lands or the budget is spent.
  size_t next = 0;
  uint64_t stream = 1;
  const int first_share = (options.max_evaluations - result.evaluations) / options.local_starts;
  for (bool solved = false; !solved && !timed_out;) {
    std::vector<size_t> unfinished;
    for (size_t i = 0; i < polished.size(); ++i)
      if (!polished[i].converged()) unfinished.push_back(i);
    const bool continuing = !unfinished.empty();
    const int left = options.max_evaluations - result.evaluations;
    const size_t available = continuing ? unfinished.size() : starts.size() - next;
    // New starts get the first pass's share each, so none is started only to be cut
    // short; continuations share what is left.
    const int minimum = continuing ? kMinContinueEvaluations : std::max(kMinPolishEvaluations, first_share);
    const int n = std::min({static_cast<int>(std::min<size_t>(options.local_starts, available)),
                            left / minimum});
    if (n <= 0) break;
    const int each = left / n;
    const double time_left = seconds_left();
    if (time_left <= 0.0) {
      timed_out = true;
      break;
    }
    // Each start gets its share of the time left, as of the evaluations.
    const double time_each = time_left * std::min(n, options.threads) / n;
    std::vector<Polish> pass(static_cast<size_t>(n));
    run_parallel(n, options.threads, [&](int i) {
      const physics::Shot& from =
          continuing ? polished[unfinished[i]].best.shot : starts[next + i].shot;
      pass[i] = polish(problem, options, search_sim, from, each, time_each, stream + i);
    });
    stream += static_cast<uint64_t>(n);
    int spent = 0;
    for (int i = 0; i < n; ++i) {
      Polish& p = pass[i];
      result.evaluations += p.evaluations;
      spent += p.evaluations;
      timed_out = timed_out || detail::out_of_time(p.code);
      solved = solved || p.best.score <= tol;
      if (!continuing) {
        polished.push_back(p);
        continue;
      }
      // A continuation keeps the better point and reports how it ended itself.
      Polish& q = polished[unfinished[i]];
      if (p.best.score > q.best.score) p.best = q.best;
      p.evaluations += q.evaluations;
      q = p;
    }
    if (!continuing) next += static_cast<size_t>(n);
    if (spent == 0) break;  // NLopt refused to run: another pass would do the same
  }
  const size_t families_left = starts.size() - next;
  result.local_searches = static_cast<int>(polished.size());
  bool out_of_evaluations = false;
  for (const Polish& p : polished) {
    if (p.converged()) ++result.converged_searches;
    else out_of_evaluations = out_of_evaluations || detail::out_of_evaluations(p.code);
  }
  if (polished.empty() && global.best().score < kInf) {
    // Nothing could be polished (no budget left): report the global stage's best.
    Polish p;
    p.best = global.best();
    p.code = NLOPT_MAXEVAL_REACHED;
    polished.push_back(p);
    out_of_evaluations = !timed_out;
  }

  // 3. Describe each polished shot; with the table, verify it with the exact method.
  const bool verify = options.verify_exact &&
                      physics::chosen_impact_method(problem.scene, sim) == physics::ImpactMethod::table;
  physics::SimulationOptions exact = sim;
  exact.impact_method = physics::ImpactMethod::exact;
  exact.impact_accuracy = kExactAccuracy;
  exact.table = nullptr;
  const physics::SimulationOptions& report_sim = verify ? exact : sim;
  std::vector<Final> finals;
  for (size_t i = 0; i < polished.size(); ++i) {
    physics::Shot shot = polished[i].best.shot;
    auto describe = [&](const physics::Shot& s) {
      const physics::ShotResult r = physics::simulate(problem.scene, problem.cue_ball, s, report_sim);
      ++result.evaluations;
      return Final{detail::describe_outcome(problem, s, r, options.enforce_rigid_limit),
                   detail::shot_score(problem, r, options.enforce_rigid_limit)};
    };
    Final f = describe(shot);
    if (verify && !f.shot.solves && polished[i].best.score <= tol && seconds_left() > 0.0) {
      const Polish again =
          polish(problem, options, exact, shot, kVerifyEvaluations, seconds_left(), kVerifyStream + i);
      result.evaluations += again.evaluations;
      if (again.best.score < f.score) f = describe(again.best.shot);
    }
    finals.push_back(std::move(f));
  }

  // 4. One shot per family (the best), each with its success probability.
  auto estimate = [&](Final& f) {
    if (options.robustness_samples == 0) return;
    f.shot.success_probability = success_probability(problem, f.shot.shot, options.noise,
                                                     options.robustness_samples, options.seed, sim);
    result.evaluations += options.robustness_samples;
  };
  auto dedupe_and_rank = [&] {
    std::map<std::string, Final> by_family;
    for (Final& f : finals) {
      auto [it, inserted] = by_family.try_emplace(f.shot.family, f);
      if (!inserted && better(f, it->second)) it->second = f;
    }
    finals.clear();
    for (auto& [family, f] : by_family) finals.push_back(std::move(f));
    std::stable_sort(finals.begin(), finals.end(), better);
  };
  dedupe_and_rank();
  for (Final& f : finals)
    if (f.shot.solves) estimate(f);
  std::stable_sort(finals.begin(), finals.end(), better);
  // The solved shots, or the best unsolved one when none is solved.
  const bool any_solved = !finals.empty() && finals.front().shot.solves;
  if (any_solved) {
    std::erase_if(finals, [](const Final& f) { return !f.shot.solves; });
  } else if (!finals.empty()) {
    finals.resize(1);
    estimate(finals.front());
  }
  const size_t keep = static_cast<size_t>(options.max_alternatives) + 1;
  if (finals.size() > keep) finals.resize(keep);

  // 5. Robust mode: polish each solved shot for its chance under the noise.
  int robust_improved = 0;
  if (options.robust && any_solved && seconds_left() > 0.0) {
    const std::vector<detail::NoiseDraw> draws = detail::noise_draws(
        options.robust_search_samples, detail::stream_seed(options.seed, kRobustStream));
    const int n = static_cast<int>(finals.size());
    const int simulations_each = options.robust_max_evaluations / n;
    const int calls_each = simulations_each / (options.robust_search_samples + 1);
    std::vector<std::pair<physics::Shot, int>> robust(static_cast<size_t>(n));
    const double time_left = seconds_left();
    if (calls_each >= 1) {
      run_parallel(n, options.threads, [&](int i) {
        const physics::Shot& start = finals[i].shot.shot;
        const SearchSpace local(problem.limits, start.aim_deg);
        RobustObjective objective(problem, local, search_sim, options, draws);
        std::vector<double> x = local.point(start);
        StageSettings s;
        s.algorithm = detail::nlopt_local(options.local);
        s.max_evaluations = calls_each;
        s.max_time_s = time_left;
        s.x_tolerance = kXTolerance;
        s.f_tolerance = 1e-4;
        s.initial_step = kPolishStep;
        nlopt_srand(detail::stream_seed(options.seed, kRobustStream + 1 + i));
        detail::run_stage(s, &x, &objective);
        robust[i] = {objective.simulations() > 0 ? objective.best() : start, objective.simulations()};
      });
      for (int i = 0; i < n; ++i) {
        result.evaluations += robust[i].second;
        const physics::ShotResult r =
            physics::simulate(problem.scene, problem.cue_ball, robust[i].first, report_sim);
        ++result.evaluations;
        Final f{detail::describe_outcome(problem, robust[i].first, r, options.enforce_rigid_limit),
                detail::shot_score(problem, r, options.enforce_rigid_limit)};
        if (!f.shot.solves) continue;
        estimate(f);
        if (f.shot.success_probability > finals[i].shot.success_probability) {
          finals[i] = std::move(f);
          ++robust_improved;
        }
      }
      dedupe_and_rank();
    }
  }

  // 6. Status and the sentence that explains it.
  if (finals.empty()) {
    result.status = timed_out ? PlanStatus::budget_exhausted : PlanStatus::unreachable;
    result.message = timed_out ? format("The time budget (%.3g s) ran out before any shot could be "
                                        "simulated.", options.max_time_s)
                               : "No shot within the limits could be simulated.";
    return finish();
  }
  result.best = finals.front().shot;
  for (size_t i = 1; i < finals.size(); ++i) result.alternatives.push_back(finals[i].shot);
  const PlannedShot& best = result.best;
  std::string where = format("%s (%s) stops %s from the target (tolerance %s)", best.family.c_str(),
                             describe_stroke(best.shot).c_str(), mm(best.miss_distance).c_str(),
                             mm(tol).c_str());
  if (best.solves) {
    result.status = PlanStatus::solved;
    result.message = "Solved: " + where;
    if (options.robustness_samples > 0)
      result.message += format(" and lands in %.0f %% of strokes with a player's error",
                               100.0 * best.success_probability);
    result.message += ".";
    if (!result.alternatives.empty())
      result.message += format(" %zu other way%s found.", result.alternatives.size(),
                               result.alternatives.size() == 1 ? "" : "s");
    if (options.robust)
      result.message += format(" Robust polish improved %d of %zu shots.", robust_improved,
                               finals.size());
  } else {
    if (!best.violations.empty()) where += "; but " + best.violations;
    if (timed_out) {
      result.status = PlanStatus::budget_exhausted;
      result.message = format("Budget exhausted: the time budget (%.3g s) ran out before a shot "
                              "reached the target. The closest found: ", options.max_time_s) +
                       where + ". Allow more time (max_time_s).";
    } else if (out_of_evaluations) {
      result.status = PlanStatus::budget_exhausted;
      result.message = format("Budget exhausted: the evaluation budget (%d shot simulations) ran "
                              "out before a shot reached the target. The closest found: ",
                              options.max_evaluations) +
                       where + ". Allow more evaluations (max_evaluations).";
    } else if (result.local_searches < std::min<int>(options.local_starts, static_cast<int>(starts.size()))) {
      // Every polish converged, but fewer than local_starts fitted in the budget: the
      // search has not looked far enough to call the target unreachable.
      result.status = PlanStatus::budget_exhausted;
      result.message = format("Budget exhausted: the evaluation budget (%d shot simulations) left "
                              "room for only %d of %d local searches, and none reached the target. "
                              "The closest found: ",
                              options.max_evaluations, result.local_searches,
                              std::min<int>(options.local_starts, static_cast<int>(starts.size()))) +
                       where + ". Allow more evaluations (max_evaluations).";
    } else {
      result.status = PlanStatus::unreachable;
      result.message = "Unreachable within the limits: the closest shot found, " + where +
                       format(". All %d local searches converged (or stopped improving) after %d shot simulations, so no "
                              "stroke within the limits seems to reach the target",
                              result.local_searches, result.evaluations);
      result.message += families_left > 0
                            ? format(" (%zu weaker candidate routes were not polished).", families_left)
                            : ".";
    }
  }
  if (best.rigid_limit_exceeded && !options.enforce_rigid_limit)
    result.message += format(" Note: the cue ball meets a cushion at %.2f m/s normal speed, above "
                             "the %.1f m/s up to which the rigid-cushion model is trusted.",
                             best.max_cushion_normal_speed, detail::kRigidLimit);
  return finish();
}

}  // namespace cueplan::planner
