// plan(): global search, local polish per family, verification, robustness.
//
// Stages, in order (Planning::run):
//   1. check    - the options and the problem (problems::validate), once;
//   2. global   - NLopt's global method over the unit cube of strokes, remembering the
//                 best stroke of every family (route and spin) it meets: half the
//                 budget from kReferenceSeed (the same families whatever the seed),
//                 then half from the seed;
//   3. polish   - the local method from the best stroke of each of the best families,
//                 in parallel, each start on its own seeded stream; while the budget
//                 allows, polishes still improving are continued and, once all have
//                 converged, the next families are started;
//   4. verify   - with the impact table, the polished strokes are simulated again
//                 with the exact method (and polished with it if they moved out);
//   5. simplify - each solved shot with side is tried again with its side removed and
//                 halved, re-polished with that side held when it no longer lands;
//   6. rank     - the success of every solved shot on the same noise draws (from
//                 kReferenceSeed, whatever the seed); a side
//                 variant the samples cannot tell from its parent replaces it; then the
//                 coach's order (ranking.hpp) and one shot per family;
//   7. robust   - (--robust) each solved shot polished for its success probability;
//   8. report   - status and a sentence a coach can read.
//
// One deadline bounds every stage; the search (global and polish) ends by
// kSearchTimeShare of it and the exact verification and side variants by
// kRefineTimeShare, so that the Monte Carlo has time left when the clock, not the
// evaluation budget, ends the search.
#include <fmt/format.h>
#include <nlopt.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "cueplan/physics/parallel.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/position.hpp"
#include "kick.hpp"
#include "nlopt_stage.hpp"
#include "ompl_stage.hpp"
#include "outcome.hpp"
#include "ranking.hpp"
#include "robustness.hpp"
#include "search_space.hpp"
#include "task.hpp"

namespace cueplan::planner {
namespace {

using Clock = std::chrono::steady_clock;
using detail::FamilyKey;
using detail::SearchSpace;
using detail::StageSettings;
using detail::Task;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPolishStop = 0.1;       // a polish stops at a miss of 10 % of the tolerance
constexpr double kPolishStep = 0.01;      // first step of a polish, unit-cube coordinates
constexpr double kXTolerance = 1e-5;      // unit-cube coordinates
constexpr double kFTolerance = 2e-5;      // m
constexpr int kMinPolishEvaluations = 100;  // a new polish needs this much budget
constexpr int kMinContinueEvaluations = 40;  // and a continued one this much
constexpr int kVerifyEvaluations = 200;
constexpr int kSimplifyEvaluations = 150;  // polish of a side variant, held side
constexpr int kMinPolish = 10;             // fewer left than this: a variant is not polished
constexpr double kSearchTimeShare = 0.75;  // of max_time_s: the global stage and the polish
constexpr double kRefineTimeShare = 0.9;   // and the exact verification and side variants
constexpr double kZoneGridScore = 0.4;  // position grid strokes worth >= 0.6 of the best
constexpr int kZoneCandidates = 3;      // of them, raced beside the polished shots
constexpr size_t kOpeningRound = 10;  // noise draws every candidate is sampled on first,
constexpr size_t kFirstRound = 50;    // then on these before the race may drop any
constexpr double kSameLanding = 1e-3;      // of the tolerance: side that moved nothing  // of max_time_s, for the global stage and the polish
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
constexpr uint64_t kSimplifyStream = 1u << 22;
constexpr int kKickFinals = 4;    // kick routes are played until this many strokes solve
constexpr int kKickPerRoute = 2;  // solved strokes (spins) kept of one route

std::string mm(double metres) {
  if (!std::isfinite(metres)) return "no rest position";
  return metres < 0.1 ? fmt::format("{:.1f} mm", 1e3 * metres) : fmt::format("{:.3g} m", metres);
}

// A stroke and its nominal score.
struct Candidate {
  physics::Shot shot;
  double score = kInf;
};

// The stroke at u of the unit cube played: *shot is it, *simulations counts what it cost.
// A pot's aim is solved for the speed and spin at u (PotAim), from *offset_hint (the last
// stroke's allowance for throw, updated: the search moves in small steps).
physics::ShotResult play(const Task& task, const SearchSpace& space, const double* u,
                         const physics::SimulationOptions& simulation, double* offset_hint,
                         physics::Shot* shot, int* simulations) {
  *shot = space.shot(u);
  if (!task.pot_aim) {
    ++*simulations;
    return task.simulate(*shot, simulation);
  }
  detail::PotAim::Aimed aimed = task.pot_aim->aim(
      task, *shot, simulation, *offset_hint, space.pot_offset(u) * task.pot_aim->lateral_reach());
  *simulations += aimed.simulations;
  *shot = aimed.shot;
  if (aimed.found)
    *offset_hint = detail::wrap_degrees(shot->aim_deg - task.pot_aim->ghost_aim_deg() +
                                        detail::squirt_of(task.problem, *shot));
  return std::move(aimed.result);
}

// The nominal objective: simulate the stroke at u, score it, count it, and (in the
// global stage) remember the best stroke of each family.
class NominalObjective {
 public:
  NominalObjective(const Task& task, const SearchSpace& space,
                   const physics::SimulationOptions& simulation, bool enforce_rigid_limit,
                   bool record_families)
      : task_(task), space_(space), simulation_(simulation),
        enforce_rigid_limit_(enforce_rigid_limit), record_families_(record_families) {}

  double operator()(const double* u) {
    physics::Shot shot;
    physics::ShotResult r = play(task_, space_, u, simulation_, &offset_hint_, &shot, &evaluations_);
    const double f = detail::shot_score(task_.problem, r, enforce_rigid_limit_) + task_.next_score(r);
    last_ = {f, r.final_position, r.status == physics::ShotStatus::rest};
    last_shot_ = shot;
    if (f < best_.score) best_ = {shot, f};
    best_history_.push_back(best_.score);
    if (record_families_) {
      auto [it, inserted] = families_.try_emplace(detail::family_key(shot, r));
      if (f < it->second.score) it->second = {shot, f};
    }
    last_result_ = std::move(r);
    return f;
  }

  int evaluations() const { return evaluations_; }
  const int* simulations_counter() const { return &evaluations_; }
  const Candidate& best() const { return best_; }
  // The stroke last scored: its score and where it stopped.
  const detail::Landing& last() const { return last_; }
  const physics::Shot& last_shot() const { return last_shot_; }
  const physics::ShotResult& last_result() const { return last_result_; }
  // True when the best score has stopped falling toward `target` (see kHorizon).
  bool stalled(double target) const {
    const size_t n = best_history_.size();
    if (n < 2 * static_cast<size_t>(kStallEvaluations)) return false;
    const double fall = best_history_[n / 2 - 1] - best_.score;  // over the last half
    return fall <= kProgress || kHorizon * fall < best_.score - target;
  }
  const std::map<FamilyKey, Candidate>& families() const { return families_; }
  // The families met so far, forgetting them: the next run's are its own.
  std::map<FamilyKey, Candidate> take_families() { return std::exchange(families_, {}); }

 private:
  const Task& task_;
  const SearchSpace& space_;
  const physics::SimulationOptions& simulation_;
  bool enforce_rigid_limit_;
  bool record_families_;
  int evaluations_ = 0;
  double offset_hint_ = 0.0;  // a pot: the last aim found less the ghost-ball aim, less its
                              // squirt (deg): the allowance for throw
  std::vector<double> best_history_;  // best score after each evaluation
  Candidate best_;
  detail::Landing last_;
  physics::Shot last_shot_;
  physics::ShotResult last_result_;
  std::map<FamilyKey, Candidate> families_;
};

// The robust objective: 1 - the soft success over common noise draws, plus a
// penalty that keeps the nominal stroke inside the landing zone.
class RobustObjective {
 public:
  RobustObjective(const Task& task, const SearchSpace& space,
                  const physics::SimulationOptions& simulation, const PlannerOptions& options,
                  const std::vector<detail::NoiseDraw>& draws)
      : task_(task), space_(space), simulation_(simulation), options_(options),
        draws_(draws) {}

  double operator()(const double* u) {
    physics::Shot shot;
    const physics::ShotResult r = play(task_, space_, u, simulation_, &offset_hint_, &shot, &simulations_);
    const double nominal =
        detail::shot_score(task_.problem, r, options_.enforce_rigid_limit) + task_.next_score(r);
    const double tol = task_.problem.tolerance;
    const double outside = std::max(0.0, nominal - 0.8 * tol) / tol;
    const double f = 1.0 - detail::soft_success(task_, shot, draws_, options_.noise,
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
  const Task& task_;
  const SearchSpace& space_;
  const physics::SimulationOptions& simulation_;
  const PlannerOptions& options_;
  const std::vector<detail::NoiseDraw>& draws_;
  int simulations_ = 0;
  double offset_hint_ = 0.0;  // a pot: the last aim found less the ghost-ball aim, less its
                              // squirt (deg): the allowance for throw
  double best_score_ = kInf;
  physics::Shot best_;
};

// Where across the pocket `shot` sends the pot's ball, as SearchSpace::pot_offset
// counts it (one simulation); 0 without a pot.
double start_pot_offset(const Task& task, const physics::Shot& shot,
                        const physics::SimulationOptions& simulation) {
  if (!task.pot_aim) return 0.0;
  const std::optional<double> lateral = task.pot_aim->lateral_of(task.simulate(shot, simulation));
  return lateral ? std::clamp(*lateral / task.pot_aim->lateral_reach(), -1.0, 1.0) : 0.0;
}

// One local polish and how it ended.
struct Polish {
  Candidate best;
  nlopt_result code = NLOPT_FAILURE;
  int evaluations = 0;
  bool stalled = false;  // see NominalObjective::stalled

  // Ended on its own tolerances, or stopped making progress before its budget ended.
  bool converged() const { return detail::converged(code) || stalled; }
};

// A local polish from `start`; with `held_sidespin_k`, over speed, aim and topspin only.
Polish polish(const Task& task, const PlannerOptions& options,
              const physics::SimulationOptions& simulation, const physics::Shot& start,
              int max_evaluations, double max_time_s, uint64_t stream,
              std::optional<double> held_sidespin_k = std::nullopt) {
  const problems::Problem& problem = task.problem;
  // Centre a free aim on the start, so the polish never meets the seam at +-180.
  const SearchSpace space(problem.limits, start.aim_deg, held_sidespin_k, task.pot_aim.has_value());
  NominalObjective objective(task, space, simulation, options.enforce_rigid_limit, false);
  std::vector<double> x = space.point(start, start_pot_offset(task, start, simulation));
  StageSettings s;
  s.algorithm = detail::nlopt_local(options.local);
  s.max_evaluations = std::max(1, max_evaluations);
  if (task.pot_aim) {
    // A pot's call costs the few simulations of its aim root: they are the budget.
    s.simulations = objective.simulations_counter();
    s.max_simulations = std::max(1, max_evaluations);
  }
  s.max_time_s = max_time_s;
  s.stop_value = kPolishStop * problem.tolerance;
  s.x_tolerance = kXTolerance;
  s.f_tolerance = kFTolerance;
  s.initial_step = kPolishStep;
  nlopt_srand(detail::stream_seed(options.seed, stream));
  Polish p;
  p.code = detail::run_stage(s, &x, &objective);
  p.best = objective.best();
  p.evaluations = objective.evaluations() + (task.pot_aim ? 1 : 0);  // and start_pot_offset's
  p.stalled = objective.stalled(problem.tolerance);
  if (objective.evaluations() == 0) p.best = {start, kInf};
  return p;
}

// A described shot with its nominal score and its noisy strokes' outcomes, for ranking.
struct Final {
  PlannedShot shot;
  double score = kInf;
  detail::Sampled sampled;        // its noisy strokes, on the common noise draws
  int id = -1;                    // its place among the shots described
  int parent = -1;                // a side variant: the id of the shot it simplifies
};

// Solved first, then the nearer: how one shot per family is kept before the noise
// is sampled, and which unsolved shot is reported when none is solved.
bool nominally_better(const Final& a, const Final& b) {
  if (a.shot.solves != b.shot.solves) return a.shot.solves;
  if (a.score != b.score) return a.score < b.score;
  return a.shot.miss_distance < b.shot.miss_distance;
}

// How a search ended, decided before it is worded (as Ceres keeps Solver::Summary
// apart from its BriefReport): the outcome and the numbers the report quotes.
enum class PlanOutcome {
  solved,
  no_kick_made,               // only kick or bank routes, none a legal stroke
  nothing_simulated_in_time,  // the clock ran out before any shot
  nothing_simulated,          // no shot within the limits could be simulated
  out_of_time,                // unsolved when the time budget ran out
  out_of_evaluations,         // unsolved when the evaluation budget ran out
  too_few_searches,           // unsolved: fewer local searches fitted than asked for
  no_solution,                // unsolved after every local search converged
};

struct PlanSummary {
  PlanOutcome outcome = PlanOutcome::nothing_simulated;
  double max_time_s = 0.0;
  int max_evaluations = 0;
  bool robust = false;
  bool enforce_rigid_limit = false;
  bool kicked = false;        // the finals include kicks
  int kick_routes_tried = 0;
  int robust_improved = 0;    // shots the robust polish improved
  size_t finals = 0;          // shots kept, one per family
  int searched = 0;           // local searches asked for, at most the families
  size_t families_left = 0;   // candidate routes never polished

  PlanStatus status() const {
    switch (outcome) {
      case PlanOutcome::solved: return PlanStatus::solved;
      case PlanOutcome::nothing_simulated_in_time:
      case PlanOutcome::out_of_time:
      case PlanOutcome::out_of_evaluations:
      case PlanOutcome::too_few_searches: return PlanStatus::budget_exhausted;
      case PlanOutcome::no_kick_made:
      case PlanOutcome::nothing_simulated:
      case PlanOutcome::no_solution: return PlanStatus::no_solution_found;
    }
    return PlanStatus::no_solution_found;
  }
};

// The sentence that explains a summary: the stroke found in a player's words, how it
// fares and what to change. `result` holds the reported strokes and the search's counts.
std::string brief_report(const PlanSummary& s, const problems::Problem& problem,
                         const PlanResult& result) {
  const double tol = problem.tolerance;
  if (s.outcome == PlanOutcome::no_kick_made) {
    std::string ruled;
    for (const std::string& r : result.ruled_out) ruled += (ruled.empty() ? "" : "; ") + r;
    return fmt::format(
        "No solution found: {} kick or bank route{} within the limits, {} tried on the exact "
        "model (speeds and spins, aim solved for each), and none made a legal stroke within "
        "the time budget ({:.3g} s){}.",
        result.kick_routes, result.kick_routes == 1 ? "" : "s", s.kick_routes_tried,
        s.max_time_s, ruled.empty() ? "" : "; ruled out: " + ruled);
  }
  if (s.outcome == PlanOutcome::nothing_simulated_in_time)
    return fmt::format("The time budget ({:.3g} s) ran out before any shot could be simulated.",
                       s.max_time_s);
  if (s.outcome == PlanOutcome::nothing_simulated)
    return "No shot within the limits could be simulated.";
  std::string message;
  const PlannedShot& best = result.best;
  std::string where = fmt::format("{} ({}) stops {} from the target (tolerance {})", best.family,
                                  describe_stroke(best.shot), mm(best.miss_distance), mm(tol));
  if (problem.is_escape())
    where = fmt::format("{} ({}) {}", best.family, describe_stroke(best.shot),
                        best.solves ? "makes a legal hit (" + *problem.first_contact + " first)"
                                    : "fails: " + best.failure_reason);
  if (problem.pot) {
    const std::string pot = fmt::format("{} ({}) {} {} in the {} pocket", best.family,
                                        describe_stroke(best.shot),
                                        best.pot && best.pot->made ? "pots" : "does not pot",
                                        problem.pot->ball,
                                        problems::pocket_name(problem.scene, problem.pot->pocket));
    where = problem.has_target
                ? fmt::format("{} and stops {} from the target (tolerance {})", pot,
                              mm(best.miss_distance), mm(tol))
                : pot;
  }
  if (s.kicked && !best.route_words.empty()) where += ": " + best.route_words + ",";
  if (s.outcome == PlanOutcome::solved) {
    message = "Solved: " + where;
    const Estimate& e = best.success.both;
    if (e.samples > 0)
      message += fmt::format(
          " and succeeds in {:.0f} % of strokes with a player's error (95 % interval {:.0f}-{:.0f} "
          "%)",
          100.0 * e.p, 100.0 * e.low, 100.0 * e.high);
    if (best.opponent_pot)
      message += fmt::format("; it leaves the opponent at best a {:.0f} % pot",
                             100.0 * *best.opponent_pot);
    if (e.samples > 0 && best.success.pot && (problem.has_target || best.success.next))
      message += fmt::format("; the pot alone {:.0f} % ({:.0f}-{:.0f} %)",
                             100.0 * best.success.pot->p, 100.0 * best.success.pot->low,
                             100.0 * best.success.pot->high);
    if (e.samples > 0 && best.success.next)
      message += fmt::format("; the next pot ({} into the {}) {:.0f} % ({:.0f}-{:.0f} %)",
                             problem.next.front().ball,
                             problems::pocket_name(problem.scene, problem.next.front().pocket),
                             100.0 * best.success.next->p, 100.0 * best.success.next->low,
                             100.0 * best.success.next->high);
    message += ".";
    if (!result.alternatives.empty())
      message += fmt::format(" {} other way{} found.", result.alternatives.size(),
                             result.alternatives.size() == 1 ? "" : "s");
    if (s.robust)
      message += fmt::format(" Robust polish improved {} of {} shots.", s.robust_improved,
                             s.finals);
  } else {
    if (!best.violations.empty()) where += "; but " + best.violations;
    if (s.outcome == PlanOutcome::out_of_time) {
      message = fmt::format("Budget exhausted: the time budget ({:.3g} s) ran out before a "
                            "shot reached the target. The closest found: ",
                            s.max_time_s) +
                where + ". Allow more time (max_time_s).";
    } else if (s.outcome == PlanOutcome::out_of_evaluations) {
      message = fmt::format("Budget exhausted: the evaluation budget ({} shot simulations) "
                            "ran out before a shot reached the target. The closest found: ",
                            s.max_evaluations) +
                where + ". Allow more evaluations (max_evaluations).";
    } else if (s.outcome == PlanOutcome::too_few_searches) {
      message = fmt::format("Budget exhausted: the evaluation budget ({} shot simulations) "
                            "left room for only {} of {} local searches, and none reached "
                            "the target. The closest found: ",
                            s.max_evaluations, result.local_searches, s.searched) +
                where + ". Allow more evaluations (max_evaluations).";
    } else {
      message =
          "No solution found within the limits: the closest shot found, " + where +
          fmt::format(". All {} local searches converged (or stopped improving) after {} shot "
                      "simulations, so no stroke within the limits seems to reach the target",
                      result.local_searches, result.evaluations);
      message += s.families_left > 0
                     ? fmt::format(" ({} weaker candidate routes were not polished).",
                                   s.families_left)
                     : ".";
    }
  }
  if (best.rigid_limit_exceeded && !s.enforce_rigid_limit)
    message += fmt::format(" Note: the cue ball meets a cushion at {:.2f} m/s normal "
                           "speed, above the {:.1f} m/s up to which the rigid-cushion "
                           "model is trusted.",
                           best.max_cushion_normal_speed,
                           problem.scene.ball_and_cushion.rigid_speed_limit);
  return message;
}

// Everything one plan() call works with, and the stages that fill it in order.
class Planning {
 public:
  Planning(const problems::Problem& problem, const PlannerOptions& options)
      : problem_(problem), options_(options), started_(Clock::now()),
        deadline_(after(started_, options.max_time_s)),
        search_deadline_(after(started_, kSearchTimeShare * options.max_time_s)),
        refine_deadline_(after(started_, kRefineTimeShare * options.max_time_s)) {}

  PlanResult run() {
    if (check()) {
      Task task(problem_, options_.solve_pot_aim);
      if (!problem_.next.empty()) {
        task.next_field = options_.position_cache
                              ? options_.position_cache->get(problem_, options_.noise)
                              : std::make_shared<const PositionField>(
                                    PositionField::for_problem(problem_, options_.noise));
        result_.position_field = task.next_field;
        task.landing_speed_sd = options_.noise.speed * options_.noise.scale;
      }
      if (direct_search()) {
        global_stage(task);
        polish_stage(task);
        verify_stage(task);
        simplify_stage(task);
      }
      kick_stage(task);
      if (!unreachable_) {
        rank_stage(task);
        robust_stage(task);
        leave_stage(task);
        report_stage(task);
      }
    }
    result_.time_s = std::chrono::duration<double>(Clock::now() - started_).count();
    return std::move(result_);
  }

 private:
  static Clock::time_point after(Clock::time_point t, double seconds) {
    return t + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  }
  double seconds_left() const {
    return std::chrono::duration<double>(deadline_ - Clock::now()).count();
  }
  double search_seconds_left() const {
    return std::chrono::duration<double>(search_deadline_ - Clock::now()).count();
  }
  double refine_seconds_left() const {
    return std::chrono::duration<double>(refine_deadline_ - Clock::now()).count();
  }

  // 1. The options, then the problem; nothing else checks them again.
  bool check() {
    if (physics::Validation e = options_.validate()) {
      result_.message = e->message();
      result_.error = std::move(e);
      return false;
    }
    if (physics::Validation e = problems::validate(problem_)) {
      result_.message = "problem: " + problems::file_message(*e);
      result_.error = std::move(e);
      return false;
    }
    screen_ = problems::screened_pot(problem_);
    if (screen_ && !kicks_allowed()) {
      result_.status = PlanStatus::unreachable;
      result_.ruled_out.push_back("direct: " + screen_->reason);
      result_.message = "Unreachable: " + screen_->reason +
                        " (the limits allow no kick or bank: limits.cushions_before_contact and "
                        "limits.object_cushions are 0; kisses and plants are not planned).";
      unreachable_ = true;
      return false;
    }
    sim_ = options_.simulation;
    sim_.record_path = false;
    verify_ = options_.verify_exact &&
              physics::chosen_impact_method(problem_.scene, sim_) == physics::ImpactMethod::table;
    exact_ = sim_;
    exact_.impact_method = physics::ImpactMethod::exact;
    exact_.impact_accuracy = kExactAccuracy;
    exact_.table = nullptr;
    // The search's own copy cuts strokes that run on around the table short.
    search_sim_ = sim_;
    search_sim_.max_events = detail::search_event_cap(problem_, sim_.max_events);
    return true;
  }

  // Whether the normal search (global, polish, verify, simplify) plans this problem: not
  // an escape (planned by its routes), not a screened pot, and not when the limits ask for
  // cushions before the contact or off the object ball.
  bool direct_search() const {
    const problems::Limits& l = problem_.limits;
    if (problem_.is_escape() || screen_) return false;
    return l.cushions_before_contact_min == 0 && (!problem_.pot || l.object_cushions_min == 0);
  }
  // Whether kick and bank routes are searched: escapes, and pots struck directly (no
  // plant) whose limits allow cushions before the contact or off the pot's ball.
  bool kicks_allowed() const {
    const problems::Limits& l = problem_.limits;
    if (problem_.is_escape()) return true;
    if (!problem_.pot || problem_.required_first_contact() != problem_.pot->ball) return false;
    return l.cushions_before_contact_max > 0 || l.object_cushions_max > 0;
  }

  // Kicks, banks and escapes (kick.hpp): when the direct search has not solved the
  // problem, the route families the limits allow, cheapest first, each route played
  // on its grid of speeds and spins with the aim solved on the simulator; the strokes
  // that solve join the finals for the rank stage. No clear route in any family (and
  // no direct search): unreachable, with every family's reason.
  void kick_stage(const Task& task) {
    if (!kicks_allowed()) return;
    if (std::any_of(finals_.begin(), finals_.end(), [](const Final& f) { return f.shot.solves; }))
      return;
    const detail::KickFamilies families = detail::kick_families(problem_, problem_.is_escape());
    const problems::Limits& l = problem_.limits;
    const bool direct_allowed =
        l.cushions_before_contact_min == 0 && (!problem_.pot || l.object_cushions_min == 0);
    if (screen_ && direct_allowed) result_.ruled_out.push_back("direct: " + screen_->reason);
    for (const std::string& why : families.ruled_out) result_.ruled_out.push_back(why);
    result_.kick_routes = static_cast<int>(families.routes.size());
    // Screened cushion routes, once the clear ones have failed: the rebound and side
    // bend a kick off its mirror line, and may take it round the screen.
    if (families.routes.empty() && !try_routes(task, families.screened)) {
      if (direct_search()) return;  // the direct search's answer stands
      result_.status = PlanStatus::unreachable;
      std::string why;
      for (const std::string& r : result_.ruled_out) why += (why.empty() ? "" : "; ") + r;
      result_.message = "Unreachable: no direct, kick or bank route within the limits (" + why +
                        "). Routes are judged on their mirror lines, two radii clear of every ball.";
      unreachable_ = true;
      return;
    }
    if (families.routes.empty()) return;  // solved round a screen, with side
    kick_tried_ = true;
    if (!try_routes(task, families.routes)) try_routes(task, families.screened);
  }

  // Plays `routes` in order until kKickFinals strokes solve or the refine deadline; the
  // strokes that solve (on the exact re-check) join the finals. True when any did.
  bool try_routes(const Task& task, const std::vector<detail::KickRoute>& routes) {
    // The exact model (a kick's aim is a root a few thousandths of a degree wide), with
    // no event cap: the pot's ball runs on after the kick.
    const physics::SimulationOptions& sim = exact_;
    int solved = 0;
    for (const detail::KickRoute& route : routes) {
      if (Clock::now() >= refine_deadline_ || solved >= kKickFinals) break;
      ++kick_routes_tried_;
      const std::vector<physics::Shot> shots = detail::solve_kick(
          task, route, sim, refine_deadline_, kKickPerRoute, &result_.evaluations);
      for (const physics::Shot& shot : shots) {
        Final f = described(task, shot);
        if (!f.shot.solves) continue;  // the exact re-check moved it out
        f.id = next_id_++;
        finals_.push_back(std::move(f));
        ++solved;
        kicked_ = true;
      }
    }
    return solved > 0;
  }

  // Position play with a pot and no target: the search's landscape is the position
  // field at the landing, flat where the next ball is screened or the cut too thin, so
  // a global method sampling a few hundred strokes can miss a zone every potting stroke
  // of some speed and spin reaches. A grid of strokes over speed, topspin and side (the
  // aim solved for each, the pot's ball sent to the pocket's middle) is scored first,
  // its families joining the reference run's: the polish starts from the best. Its
  // strokes, and a finer grid's, that land where the next pot is worth much are kept
  // for add_zone_candidates.
  bool position_grid_wanted(const Task& task) const {
    return task.next_field && task.pot_aim && !problem_.has_target && !options_.stop_at_first_solution &&
           problem_.limits.spin_max > 0.0;
  }
  void position_grid(const Task& task, const SearchSpace& space, NominalObjective* objective) {
    constexpr int kSpeeds = 6;
    constexpr double kTops[] = {-0.9, -0.45, 0.0, 0.45, 0.9};  // of the spin square
    constexpr double kSides[] = {-0.6, 0.0, 0.6};
    if (space.aim_searched() || space.dimension() != 4) return;  // speed, spin square, pot offset
    std::vector<double> u(static_cast<size_t>(space.dimension()), 0.5);
    const auto score = [&](NominalObjective* scorer, double speed_u, double side, double top) {
      u[0] = speed_u;
      u[1] = 0.5 * (side + 1.0);
      u[2] = 0.5 * (top + 1.0);
      (*scorer)(u.data());
      if (scorer->last().score <= kZoneGridScore * Task::kNextScale && scorer->last().at_rest)
        zone_grid_.emplace_back(task.landing_worth(scorer->last_result()), scorer->last_shot());
    };
    for (int v = 0; v < kSpeeds; ++v)
      for (double side : kSides)
        for (double top : kTops) {
          if (Clock::now() >= search_deadline_) return;
          score(objective, (v + 0.5) / kSpeeds, side, top);
        }
    // A finer grid for the zone candidates alone (its families are not polished: they
    // would crowd out the global method's): 10 speeds x 7 topspins x 5 sides.
    constexpr int kFineSpeeds = 10;
    constexpr double kFineTops[] = {-0.9, -0.6, -0.3, 0.0, 0.3, 0.6, 0.9};
    constexpr double kFineSides[] = {-0.6, -0.3, 0.0, 0.3, 0.6};
    NominalObjective fine(task, space, search_sim_, options_.enforce_rigid_limit, false);
    for (int v = 0; v < kFineSpeeds && Clock::now() < search_deadline_; ++v)
      for (double side : kFineSides)
        for (double top : kFineTops) score(&fine, (v + 0.5) / kFineSpeeds, side, top);
    zone_grid_evaluations_ = fine.evaluations();  // counted by add_zone_candidates
  }

  // The grid's strokes that pot and leave the cue ball where the next pot is worth at
  // least (1 - kZoneGridScore) of the best, ranked by their landing's worth with a
  // stroke's spread around it (Task::landing_worth): the best kZoneCandidates of them,
  // described as the report describes, join the polished shots in the race. The
  // polish settles where the landing is first worth the best, often a zone's edge; a
  // grid stroke in its middle, where the noisy strokes also stop, may succeed as often
  // and leave the cue ball surely in the zone.
  void add_zone_candidates(const Task& task) {
    // Every simulation here, the finer grid's included, comes on top of the budget:
    // the side variants that follow keep theirs.
    const int before = result_.evaluations;
    result_.evaluations += zone_grid_evaluations_;
    std::stable_sort(zone_grid_.begin(), zone_grid_.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    const bool in_time = refine_seconds_left() > 0.0;
    int added = 0;
    for (const auto& [worth, shot] : zone_grid_) {
      if (!in_time || added == kZoneCandidates) break;
      Final f = described(task, shot);
      if (!f.shot.solves) continue;
      finals_.push_back(std::move(f));
      ++added;
    }
    grid_evaluations_ += result_.evaluations - before;
  }

  // 2. Global stage over the whole stroke space, remembering every family's best.
  void global_stage(const Task& task) {
    const SearchSpace space(problem_.limits, 0.0, std::nullopt, task.pot_aim.has_value());
    NominalObjective global(task, space, search_sim_, options_.enforce_rigid_limit, true);
    std::map<FamilyKey, Candidate> reference;  // the families of the reference run
    const int budget =
        std::max(1, static_cast<int>(options_.global_share * options_.max_evaluations));
    if (options_.global == GlobalMethod::ompl_kpiece1) {
      detail::LandingSearch s;
      s.dimension = space.dimension();
      s.aim_coordinate =
          problem_.limits.aim.mode == problems::AimMode::free && space.aim_searched() ? 1 : -1;
      s.max_evaluations = budget;
      s.max_time_s = std::max(1e-6, options_.global_share * search_seconds_left());
      s.goal_score = problem_.tolerance;  // a stroke in the zone: the polish takes it from there
      s.table_length = problem_.scene.length;
      s.table_width = problem_.scene.width;
      s.seed = detail::stream_seed(options_.seed, 0);
      detail::explore_landings(s, [&global](const double* u) {
        global(u);
        return global.last();
      });
    } else {
      std::vector<double> x(static_cast<size_t>(space.dimension()), 0.5);
      StageSettings s;
      s.algorithm = detail::nlopt_global(options_.global);
      s.max_evaluations = budget;
      if (task.pot_aim) {
        s.simulations = global.simulations_counter();
        s.max_simulations = budget;
      }
      s.max_time_s = std::max(1e-6, options_.global_share * search_seconds_left());
      s.inner = detail::nlopt_local(options_.local);
      s.inner_max_evaluations = std::max(20, s.max_evaluations / 10);
      s.inner_x_tolerance = kXTolerance;
      s.inner_f_tolerance = kFTolerance;
      s.inner_step = kPolishStep;
      // Position play: a grid of strokes first (position_grid), on top of the budget.
      if (position_grid_wanted(task)) {
        position_grid(task, space, &global);
        grid_evaluations_ = global.evaluations();
        s.max_simulations = budget + grid_evaluations_;
      }
      // Two runs of half the budget each: the reference run, from kReferenceSeed, finds
      // the same families whatever the seed; the seeded run adds its own.
      const int reference_budget = std::max(1, budget / 2);
      const double time_s = s.max_time_s;
      s.max_evaluations = reference_budget;
      s.max_simulations = reference_budget + grid_evaluations_;
      s.max_time_s = 0.5 * time_s;
      s.inner_max_evaluations = std::max(20, s.max_evaluations / 10);
      nlopt_srand(detail::stream_seed(kReferenceSeed, 0));
      detail::run_stage(s, &x, &global);
      reference = global.take_families();
      x.assign(x.size(), 0.5);
      s.max_evaluations = std::max(1, budget + grid_evaluations_ - global.evaluations());
      s.max_simulations = budget + grid_evaluations_;  // the counter runs on from the reference run's
      s.max_time_s = std::max(1e-6, options_.global_share * search_seconds_left());
      nlopt_srand(detail::stream_seed(options_.seed, 0));
      if (global.evaluations() < budget + grid_evaluations_) detail::run_stage(s, &x, &global);
    }
    result_.evaluations += global.evaluations();
    timed_out_ = search_seconds_left() <= 0.0;
    global_best_ = global.best();

    // Starts: the reference run's families by their best score (map order breaks ties,
    // so the ranking is fixed), then those of the seeded run that it did not meet or met
    // nearer; strokes that end early are starts only when nothing else was met. The
    // polish takes them in this order, so the reference families are polished first
    // and the answer the same whatever the seed.
    const std::map<FamilyKey, Candidate> seeded = global.take_families();
    const auto by_score = [](const Candidate& a, const Candidate& b) { return a.score < b.score; };
    for (bool ended_early : {false, true}) {
      std::vector<Candidate> first, then;
      for (const auto& [key, c] : reference)
        if (key.ended_early == ended_early) first.push_back(c);
      for (const auto& [key, c] : seeded) {
        if (key.ended_early != ended_early) continue;
        const auto known = reference.find(key);
        if (known == reference.end() || c.score < known->second.score) then.push_back(c);
      }
      std::stable_sort(first.begin(), first.end(), by_score);
      std::stable_sort(then.begin(), then.end(), by_score);
      starts_ = std::move(first);
      starts_.insert(starts_.end(), then.begin(), then.end());
      if (!starts_.empty()) break;
    }
  }

  // 3. Local polish in passes of up to local_starts starts, until the budget is spent
  // or every family met has been polished. Each pass either continues the polishes
  // that ran out of evaluations while still improving (the best families first) or,
  // when all have converged, starts the next families. It does not stop at the first
  // shot that lands: the families polished after it are the alternatives the rank
  // stage chooses from (bench/README.md, "Planner", measured what that buys and costs).
  void polish_stage(const Task& task) {
    uint64_t stream = 1;
    const int first_share =
        (options_.max_evaluations + grid_evaluations_ - result_.evaluations) / options_.local_starts;
    for (bool solved = false; !(solved && options_.stop_at_first_solution) && !timed_out_;) {
      std::vector<size_t> unfinished;
      for (size_t i = 0; i < polished_.size(); ++i)
        if (!polished_[i].converged()) unfinished.push_back(i);
      const bool continuing = !unfinished.empty();
      const int left = options_.max_evaluations + grid_evaluations_ - result_.evaluations;
      const size_t available = continuing ? unfinished.size() : starts_.size() - next_start_;
      // New starts get the first pass's share each, so none is started only to be cut
      // short; continuations share what is left.
      const int minimum =
          continuing ? kMinContinueEvaluations : std::max(kMinPolishEvaluations, first_share);
      const int n = std::min(
          {static_cast<int>(std::min<size_t>(options_.local_starts, available)), left / minimum});
      if (n <= 0) break;
      const int each = left / n;
      const double time_left = search_seconds_left();
      if (time_left <= 0.0) {
        timed_out_ = true;
        break;
      }
      // Each start gets its share of the time left, as of the evaluations.
      const double time_each = time_left * std::min(n, options_.threads) / n;
      std::vector<Polish> pass(static_cast<size_t>(n));
      physics::parallel_for(static_cast<size_t>(n), physics::thread_count(options_.threads, n),
                            [&](size_t i, unsigned) {
                              const physics::Shot& from = continuing
                                                              ? polished_[unfinished[i]].best.shot
                                                              : starts_[next_start_ + i].shot;
                              pass[i] = polish(task, options_, search_sim_, from, each, time_each,
                                               stream + i);
                            });
      stream += static_cast<uint64_t>(n);
      int spent = 0;
      for (int i = 0; i < n; ++i) {
        Polish& p = pass[i];
        result_.evaluations += p.evaluations;
        spent += p.evaluations;
        timed_out_ = timed_out_ || detail::out_of_time(p.code);
        solved = solved || p.best.score <= task.landing_score();
        if (!continuing) {
          polished_.push_back(p);
          continue;
        }
        // A continuation keeps the better point and reports how it ended itself.
        Polish& q = polished_[unfinished[i]];
        if (p.best.score > q.best.score) p.best = q.best;
        p.evaluations += q.evaluations;
        q = p;
      }
      if (!continuing) next_start_ += static_cast<size_t>(n);
      if (spent == 0) break;  // NLopt refused to run: another pass would do the same
    }
    result_.local_searches = static_cast<int>(polished_.size());
    for (const Polish& p : polished_) {
      if (p.converged()) ++result_.converged_searches;
      else out_of_evaluations_ = out_of_evaluations_ || detail::out_of_evaluations(p.code);
    }
    if (polished_.empty() && global_best_.score < kInf) {
      // Nothing could be polished (no budget left): report the global stage's best.
      Polish p;
      p.best = global_best_;
      p.code = NLOPT_MAXEVAL_REACHED;
      polished_.push_back(p);
      out_of_evaluations_ = !timed_out_;
    }
  }

  // A stroke simulated for the report and described; *simulations counts it.
  Final describe_shot(const Task& task, const physics::Shot& shot, int* simulations) const {
    const physics::ShotResult r = task.simulate(shot, report_sim());
    ++*simulations;
    Final f;
    f.shot = detail::describe_outcome(problem_, shot, r, options_.enforce_rigid_limit);
    f.score = detail::shot_score(problem_, r, options_.enforce_rigid_limit) + task.next_score(r);
    return f;
  }
  Final described(const Task& task, const physics::Shot& shot) {
    return describe_shot(task, shot, &result_.evaluations);
  }

  // The simulation the reported outcomes come from: exact when the search used the table.
  const physics::SimulationOptions& report_sim() const { return verify_ ? exact_ : sim_; }

  // `shot` polished (with `held` side, if given) and described; when the exact
  // verification moves a polished stroke out of the tolerance, polished again with it.
  Final polished_and_described(const Task& task, const physics::Shot& shot, int max_evaluations,
                               uint64_t stream, std::optional<double> held, int* simulations) const {
    const Polish p = polish(task, options_, search_sim_, shot, max_evaluations,
                            std::max(1e-6, refine_seconds_left()), stream, held);
    *simulations += p.evaluations;
    Final f = describe_shot(task, p.best.shot, simulations);
    if (verify_ && !f.shot.solves && p.best.score <= task.landing_score() && refine_seconds_left() > 0.0) {
      const Polish again = polish(task, options_, exact_, p.best.shot, kVerifyEvaluations,
                                  refine_seconds_left(), stream + kVerifyStream, held);
      *simulations += again.evaluations;
      if (again.best.score < f.score) f = describe_shot(task, again.best.shot, simulations);
    }
    return f;
  }

  // 4. Describe each polished shot; with the table, verify it with the exact method.
  void verify_stage(const Task& task) {
    verify_ = options_.verify_exact &&
              physics::chosen_impact_method(problem_.scene, sim_) == physics::ImpactMethod::table;
    exact_ = sim_;
    exact_.impact_method = physics::ImpactMethod::exact;
    exact_.impact_accuracy = kExactAccuracy;
    exact_.table = nullptr;
    for (size_t i = 0; i < polished_.size(); ++i) {
      const physics::Shot shot = polished_[i].best.shot;
      Final f = described(task, shot);
      if (verify_ && !f.shot.solves && polished_[i].best.score <= task.landing_score() &&
          refine_seconds_left() > 0.0) {
        const Polish again = polish(task, options_, exact_, shot, kVerifyEvaluations,
                                    refine_seconds_left(), kVerifyStream + i);
        result_.evaluations += again.evaluations;
        if (again.best.score < f.score) f = described(task, again.best.shot);
      }
      finals_.push_back(std::move(f));
    }
    // One shot per family, the nearest first.
    std::map<Family, Final> by_family;
    for (Final& f : finals_) {
      auto [it, inserted] = by_family.try_emplace(f.shot.family_key, f);
      if (!inserted && nominally_better(f, it->second)) it->second = f;
    }
    finals_.clear();
    for (auto& [family, f] : by_family) finals_.push_back(std::move(f));
    add_zone_candidates(task);
    std::stable_sort(finals_.begin(), finals_.end(), nominally_better);
    for (Final& f : finals_) f.id = next_id_++;
  }

  // 5. Side that may do nothing: every solved shot with side is tried with no side -
  // as it is, and if it then misses, polished with the side held at zero (speed, aim
  // and topspin free). Where the side changed nothing at all (the stroke without it
  // stops within kSameLanding of the same place by the same cushions: side spent
  // before the first cushion, or no cushion at all), it replaces the shot at once;
  // otherwise the shot is also tried with half its side, and the variants that land
  // join the candidates for the rank stage to decide whether the side earned its place.
  void simplify_stage(const Task& task) {
    if (options_.stop_at_first_solution) return;
    std::vector<size_t> sided;
    for (size_t i = 0; i < finals_.size(); ++i) {
      const PlannedShot& p = finals_[i].shot;
      if (p.solves && std::abs(p.shot.sidespin_k) >= detail::kCentreK) sided.push_back(i);
    }
    const std::vector<Final> plain = variants(task, sided, 0.0, 0);
    std::vector<size_t> halve;
    std::set<int> replaced;
    for (size_t j = 0; j < plain.size(); ++j) {
      const Final& parent = finals_[sided[j]];
      const Final& v = plain[j];
      if (v.shot.solves && v.shot.route == parent.shot.route &&
          std::hypot(v.shot.final_position.x - parent.shot.final_position.x,
                     v.shot.final_position.y - parent.shot.final_position.y) <=
              kSameLanding * problem_.tolerance)
        replaced.insert(parent.id);
      else if (std::abs(0.5 * parent.shot.shot.sidespin_k) >= detail::kCentreK)
        halve.push_back(sided[j]);
    }
    const std::vector<Final> half = variants(task, halve, 0.5, plain.size());
    std::erase_if(finals_, [&](const Final& f) { return replaced.count(f.id) > 0; });
    for (const std::vector<Final>* found : {&plain, &half})
      for (const Final& f : *found) {
        if (!f.shot.solves) continue;
        finals_.push_back(f);
        finals_.back().id = next_id_++;
      }
  }

  // The shots finals_[parents[j]] with `side_factor` times their side, each as it is or,
  // when it misses, polished with that side held; in parallel, each polish on its own
  // stream (from `stream_offset`). Each variant's parent is the shot's id.
  std::vector<Final> variants(const Task& task, const std::vector<size_t>& parents,
                              double side_factor, size_t stream_offset) {
    std::vector<Final> out(parents.size());
    if (parents.empty() || refine_seconds_left() <= 0.0) return {};
    std::vector<int> simulations(parents.size(), 0);
    // A variant that misses is polished within what is left of the search's budget, less
    // the simulations that describe the variants.
    const int left = options_.max_evaluations + grid_evaluations_ - result_.evaluations -
                     2 * static_cast<int>(parents.size());
    const int polish_budget =
        std::min(kSimplifyEvaluations, std::max(0, left) / static_cast<int>(parents.size()));
    physics::parallel_for(
        parents.size(), physics::thread_count(options_.threads, static_cast<int>(parents.size())),
        [&](size_t j, unsigned) {
          physics::Shot shot = finals_[parents[j]].shot.shot;
          const double parent_squirt = detail::squirt_of(task.problem, shot);
          shot.sidespin_k = side_factor == 0.0 ? 0.0 : side_factor * shot.sidespin_k;
          // The cue ball leaves along the parent's line: the aim allows for the change of
          // squirt (a pot's aim is solved again below).
          shot.aim_deg += parent_squirt - detail::squirt_of(task.problem, shot);
          if (task.pot_aim) {
            // Side changes the throw: the aim is solved again for the new spin.
            const double lateral =
                start_pot_offset(task, shot, report_sim()) * task.pot_aim->lateral_reach();
            const detail::PotAim::Aimed aimed = task.pot_aim->aim(
                task, shot, report_sim(),
                detail::wrap_degrees(shot.aim_deg - task.pot_aim->ghost_aim_deg() + parent_squirt),
                lateral);
            simulations[j] += aimed.simulations + 1;
            shot = aimed.shot;
          }
          Final f = describe_shot(task, shot, &simulations[j]);
          if (!f.shot.solves && refine_seconds_left() > 0.0 && polish_budget >= kMinPolish)
            f = polished_and_described(task, shot, polish_budget,
                                       kSimplifyStream + stream_offset + j, shot.sidespin_k,
                                       &simulations[j]);
          f.parent = finals_[parents[j]].id;
          out[j] = std::move(f);
        });
    for (int n : simulations) result_.evaluations += n;
    return out;
  }

  // The success of each of `shots` on the common noise draws, raced: all are sampled
  // on the first kOpeningRound draws (so that a deadline leaves none without any), then
  // on the first kFirstRound, then, doubling the draws each round up to
  // robustness_samples, only those the samples cannot yet tell are worse than the
  // leader (McNemar's test, ranking.hpp). A shot dropped early keeps its shorter
  // sample (its Estimate says how many). Each round runs in parallel; the simulations
  // count as evaluations; nothing is started after the deadline.
  void estimate(const Task& task, const std::vector<Final*>& shots) {
    const size_t samples = static_cast<size_t>(options_.robustness_samples);
    if (samples == 0 || shots.empty()) return;
    std::vector<Final*> alive = shots;
    for (size_t n = std::min(samples, kOpeningRound);;
         n = std::min(samples, n < kFirstRound ? kFirstRound : 2 * n)) {
      draws_.grow_to(n, deadline_);
      const std::span<const detail::NoiseDraw> draws(draws_.draws().data(),
                                                     std::min(n, draws_.draws().size()));
      std::vector<int> before(alive.size());
      for (size_t i = 0; i < alive.size(); ++i) before[i] = alive[i]->sampled.simulations;
      physics::parallel_for(
          alive.size(), physics::thread_count(options_.threads, static_cast<int>(alive.size())),
          [&](size_t i, unsigned) {
            Final& f = *alive[i];
            detail::extend_sample(task, f.shot.shot, draws, options_.noise, sim_, deadline_,
                                  &f.sampled);
          });
      for (size_t i = 0; i < alive.size(); ++i) {
        Final& f = *alive[i];
        result_.evaluations += f.sampled.simulations - before[i];
        f.shot.success = f.sampled.success;
        f.shot.success_probability = f.sampled.success.both.p;
      }
      if (n == samples || draws.size() < n || Clock::now() >= deadline_) break;
      if (n < kFirstRound) continue;  // too few draws to tell strokes apart
      const Final* leader = alive.front();
      for (const Final* f : alive)
        if (f->sampled.success.both.p > leader->sampled.success.both.p) leader = f;
      std::erase_if(alive, [&](const Final* f) {
        return f->sampled.success.both.p < leader->sampled.success.both.p &&
               detail::significantly_different(f->sampled.outcomes, leader->sampled.outcomes);
      });
    }
  }

  // The coach's order of the (solved, estimated) finals, one shot per family.
  void coach_rank() {
    std::vector<detail::RankItem> items;
    const PositionField* field = result_.position_field.get();
    for (const Final& f : finals_)
      items.push_back({&f.sampled.outcomes, f.shot.success.both,
                       detail::effort(f.shot.shot, problem_.limits),
                       field ? field->value(f.shot.final_position) : 0.0});
    std::vector<Final> ranked;
    std::set<Family> seen;
    for (size_t i : detail::coach_order(items))
      if (seen.insert(finals_[i].shot.family_key).second) ranked.push_back(std::move(finals_[i]));
    finals_ = std::move(ranked);
  }

  // 6. The solved shots by the coach's order, each with its success; or the nearest
  // unsolved one when none is solved.
  void rank_stage(const Task& task) {
    any_solved_ = std::any_of(finals_.begin(), finals_.end(),
                              [](const Final& f) { return f.shot.solves; });
    if (!any_solved_) {
      if (finals_.empty()) return;
      finals_.resize(1);
      estimate(task, {&finals_.front()});
      return;
    }
    std::erase_if(finals_, [](const Final& f) { return !f.shot.solves; });
    std::vector<Final*> all;
    for (Final& f : finals_) all.push_back(&f);
    estimate(task, all);
    // Of a shot and its side variants, one with less side replaces one with more when
    // the samples cannot tell them apart: that side did nothing a player could count on.
    const auto root = [](const Final& f) { return f.parent >= 0 ? f.parent : f.id; };
    std::set<int> replaced;
    for (const Final& a : finals_)
      for (const Final& b : finals_)
        if (root(a) == root(b) && std::abs(b.shot.shot.sidespin_k) < std::abs(a.shot.shot.sidespin_k) &&
            !detail::significantly_different(a.sampled.outcomes, b.sampled.outcomes))
          replaced.insert(a.id);
    std::erase_if(finals_, [&](const Final& f) { return replaced.count(f.id) > 0; });
    coach_rank();
    const size_t keep = static_cast<size_t>(options_.max_alternatives) + 1;
    if (finals_.size() > keep) finals_.resize(keep);
  }

  // `leave: safe`: each solved escape's leave judged from where its cue ball stops, and
  // the escapes ranked by P(legal hit) times the chance the opponent misses the easiest
  // pot left (stable: the coach's order breaks ties).
  void leave_stage(const Task& task) {
    if (!problem_.leave_safe || !any_solved_) return;
    const double sigma = options_.noise.aim_deg * options_.noise.scale;
    for (Final& f : finals_) {
      const physics::ShotResult r = task.simulate(f.shot.shot, report_sim());
      ++result_.evaluations;
      f.shot.opponent_pot = detail::easiest_pot(problem_, r, sigma);
    }
    const auto value = [](const Final& f) {
      return f.shot.success.both.p * (1.0 - f.shot.opponent_pot.value_or(0.0));
    };
    std::stable_sort(finals_.begin(), finals_.end(),
                     [&](const Final& a, const Final& b) { return value(a) > value(b); });
  }

  // 7. Robust mode: polish each solved shot for its chance under the noise.
  void robust_stage(const Task& task) {
    // A kick's aim is its own root, not the pot's ghost-ball aim the robust polish solves.
    if (!options_.robust || !any_solved_ || kicked_ || seconds_left() <= 0.0) return;
    const std::vector<detail::NoiseDraw> draws = detail::noise_draws(
        options_.robust_search_samples, detail::stream_seed(options_.seed, kRobustStream));
    const int n = static_cast<int>(finals_.size());
    const int simulations_each = options_.robust_max_evaluations / n;
    const int calls_each = simulations_each / (options_.robust_search_samples + 1);
    if (calls_each < 1) return;
    std::vector<std::pair<physics::Shot, int>> robust(static_cast<size_t>(n));
    const double time_left = seconds_left();
    physics::parallel_for(
        static_cast<size_t>(n), physics::thread_count(options_.threads, n),
        [&](size_t i, unsigned) {
          const physics::Shot& start = finals_[i].shot.shot;
          const SearchSpace local(problem_.limits, start.aim_deg, std::nullopt,
                                  task.pot_aim.has_value());
          RobustObjective objective(task, local, search_sim_, options_, draws);
          std::vector<double> x = local.point(start, start_pot_offset(task, start, search_sim_));
          StageSettings s;
          s.algorithm = detail::nlopt_local(options_.local);
          s.max_evaluations = calls_each;
          s.max_time_s = time_left;
          s.x_tolerance = kXTolerance;
          s.f_tolerance = 1e-4;
          s.initial_step = kPolishStep;
          nlopt_srand(detail::stream_seed(options_.seed, kRobustStream + 1 + i));
          detail::run_stage(s, &x, &objective);
          robust[i] = {objective.simulations() > 0 ? objective.best() : start,
                       objective.simulations()};
        });
    std::vector<Final> candidates;
    for (int i = 0; i < n; ++i) {
      result_.evaluations += robust[i].second;
      Final f = described(task, robust[i].first);
      f.id = i;
      if (f.shot.solves) candidates.push_back(std::move(f));
    }
    std::vector<Final*> all;
    for (Final& f : candidates) all.push_back(&f);
    estimate(task, all);
    for (Final& f : candidates) {
      Final& was = finals_[static_cast<size_t>(f.id)];
      if (f.shot.success_probability > was.shot.success_probability) {
        f.parent = was.parent;
        f.id = was.id;
        was = std::move(f);
        ++robust_improved_;
      }
    }
    coach_rank();
  }

  // 8. Status and the sentence that explains it: deciding (the status, the numbers it
  // rests on, the reported strokes' extra simulations) apart from wording.
  void report_stage(const Task& task) {
    const PlanSummary summary = summarise(task);
    result_.status = summary.status();
    result_.message = brief_report(summary, problem_, result_);
  }

  // The outcome of the search and what its report quotes. Fills the best stroke, the
  // alternatives and what the reported strokes need simulated (their pots and routes in
  // a player's words), counting those simulations in result_.evaluations.
  PlanSummary summarise(const Task& task) {
    PlanResult& result = result_;
    PlanSummary s;
    s.max_time_s = options_.max_time_s;
    s.max_evaluations = options_.max_evaluations;
    s.robust = options_.robust;
    s.enforce_rigid_limit = options_.enforce_rigid_limit;
    s.kicked = kicked_;
    s.kick_routes_tried = kick_routes_tried_;
    s.robust_improved = robust_improved_;
    s.finals = finals_.size();
    if (finals_.empty()) {
      s.outcome = kick_tried_ ? PlanOutcome::no_kick_made
                  : timed_out_ ? PlanOutcome::nothing_simulated_in_time
                               : PlanOutcome::nothing_simulated;
      return s;
    }
    result.best = finals_.front().shot;
    for (size_t i = 1; i < finals_.size(); ++i) result.alternatives.push_back(finals_[i].shot);
    if (task.pot_aim) {
      // The pot of each reported stroke in a player's terms (a few simulations each).
      std::vector<PlannedShot*> reported{&result.best};
      for (PlannedShot& a : result.alternatives) reported.push_back(&a);
      for (PlannedShot* p : reported) {
        const physics::ShotResult r = task.simulate(p->shot, report_sim());
        ++result.evaluations;
        p->pot = detail::pot_report(task, *task.pot_aim, p->shot, r, report_sim(),
                                    &result.evaluations);
        p->route_words = detail::route_words(problem_, p->shot, r);
      }
    }
    if (task.next_field) {
      // What each reported stroke leaves for the next pot, from where it stops.
      // Its success.next interval also holds the chance where the stroke as planned
      // leaves the cue ball (the field's allowance either side): the player is left
      // there when the stroke is played as planned, which the noisy landings' middle
      // 80 % can miss where the zone is small.
      std::vector<PlannedShot*> reported{&result.best};
      for (PlannedShot& a : result.alternatives) reported.push_back(&a);
      for (PlannedShot* p : reported) {
        p->next = next_report(problem_, *task.next_field, p->final_position);
        if (!p->success.next || p->success.next->samples == 0) continue;
        Estimate& n = *p->success.next;
        n.low = std::min(n.low, std::max(0.0, p->next->p - kFieldError));
        n.high = std::max(n.high, std::min(1.0, p->next->p + kFieldError));
      }
    }
    if (!task.pot_aim && !problem_.required_first_contact().empty()) {
      // The route of each reported stroke in a player's words (one simulation each).
      std::vector<PlannedShot*> reported{&result.best};
      for (PlannedShot& a : result.alternatives) reported.push_back(&a);
      for (PlannedShot* p : reported) {
        const physics::ShotResult r = task.simulate(p->shot, report_sim());
        ++result.evaluations;
        p->route_words = detail::route_words(problem_, p->shot, r);
      }
    }
    s.searched = std::min<int>(options_.local_starts, static_cast<int>(starts_.size()));
    s.families_left = starts_.size() - next_start_;
    if (result.best.solves)
      s.outcome = PlanOutcome::solved;
    else if (timed_out_)
      s.outcome = PlanOutcome::out_of_time;
    else if (out_of_evaluations_)
      s.outcome = PlanOutcome::out_of_evaluations;
    else if (result.local_searches < s.searched)
      // Every polish converged, but fewer than local_starts fitted in the budget: the
      // search has not looked far enough to say that no stroke reaches the target.
      s.outcome = PlanOutcome::too_few_searches;
    else
      s.outcome = PlanOutcome::no_solution;
    return s;
  }

  const problems::Problem& problem_;
  const PlannerOptions& options_;
  const Clock::time_point started_;
  const Clock::time_point deadline_;
  const Clock::time_point search_deadline_;
  const Clock::time_point refine_deadline_;
  PlanResult result_;
  physics::SimulationOptions sim_;         // the search's simulation, without paths
  physics::SimulationOptions search_sim_;  // the same with the search's event cap
  physics::SimulationOptions exact_;       // the exact verification's
  bool verify_ = false;
  Candidate global_best_;
  std::vector<Candidate> starts_;  // the best stroke of each family, best first
  size_t next_start_ = 0;          // the first family not yet polished
  int grid_evaluations_ = 0;       // simulations of the position grid, on top of the budget
  // The grids' strokes that pot into the zone's reach, each with its landing's worth.
  std::vector<std::pair<double, physics::Shot>> zone_grid_;
  int zone_grid_evaluations_ = 0;         // simulations of the finer grid
  std::vector<Polish> polished_;
  bool timed_out_ = false;
  bool out_of_evaluations_ = false;
  std::vector<Final> finals_;
  int next_id_ = 0;  // Final::id of the next shot described for ranking
  // The common draws of every success estimate: the same whatever the seed, so that a
  // stroke's success does not depend on it.
  detail::NoiseStream draws_{kReferenceSeed};
  bool any_solved_ = false;
  bool unreachable_ = false;
  std::optional<problems::PotScreen> screen_;  // a direct pot the geometry rules out
  bool kick_tried_ = false;  // kick or bank routes were played
  bool kicked_ = false;      // and some solved: the finals include kicks
  int kick_routes_tried_ = 0;
  int robust_improved_ = 0;
};

}  // namespace

physics::Validation PlannerOptions::validate() const {
  using physics::invalid;
  auto bad = [](const char* field, const char* rule, double value) {
    return invalid({field}, rule, value);
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
  if (physics::Validation e = noise.validate()) return e->under({"noise"});
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
    return invalid({"simulation", "max_events"}, "must be at least 1", simulation.max_events);
  if (!std::isfinite(simulation.impact_accuracy) || !(simulation.impact_accuracy > 0.0))
    return invalid({"simulation", "impact_accuracy"}, "must be positive and finite",
                   simulation.impact_accuracy);
  return {};
}

namespace {

// The problem with its speed and spin limits brought within the default ones (a limit
// wider than the default narrowed to it); the same problem when they are not wider.
problems::Problem within_default_limits(const problems::Problem& problem) {
  const problems::Limits defaults;
  problems::Problem narrow = problem;
  problems::Limits& l = narrow.limits;
  l.speed_min = std::max(l.speed_min, defaults.speed_min);
  l.speed_max = std::min(l.speed_max, defaults.speed_max);
  l.spin_max = std::min(l.spin_max, defaults.spin_max);
  return narrow;
}

bool wider_than_default(const problems::Limits& limits, const problems::Limits& narrow) {
  return limits.speed_min != narrow.speed_min || limits.speed_max != narrow.speed_max ||
         limits.spin_max != narrow.spin_max;
}

}  // namespace

PlanResult plan(const problems::Problem& problem, const PlannerOptions& options) {
  PlanResult wide = Planning(problem, options).run();
  // A wider limit must never answer worse than the default one: where the speed or spin
  // limit goes beyond the default, the problem is also planned within the default limits
  // (same options and seed), and that answer is kept unless the wide search found a
  // stroke that succeeds more often. Its strokes lie within the wider limits too.
  const problems::Problem narrow = within_default_limits(problem);
  if (wide.status == PlanStatus::invalid_input || !wider_than_default(problem.limits, narrow.limits) ||
      !(narrow.limits.speed_min < narrow.limits.speed_max))
    return wide;
  PlanResult inner = Planning(narrow, options).run();
  if (inner.status != PlanStatus::solved) {
    wide.evaluations += inner.evaluations;
    wide.time_s += inner.time_s;
    return wide;
  }
  const bool keep_inner = wide.status != PlanStatus::solved ||
                          inner.best.success_probability >= wide.best.success_probability;
  PlanResult& kept = keep_inner ? inner : wide;
  const PlanResult& other = keep_inner ? wide : inner;
  kept.evaluations += other.evaluations;
  kept.time_s += other.time_s;
  kept.local_searches += other.local_searches;
  kept.converged_searches += other.converged_searches;
  return std::move(kept);
}

}  // namespace cueplan::planner
