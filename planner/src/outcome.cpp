// Scoring, families and constraint reports of single strokes, and evaluate().
#include "outcome.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "cueplan/planner/planner.hpp"

namespace cueplan::planner {
namespace detail {
namespace {

int sign_class(double k) { return std::abs(k) < kCentreK ? 0 : (k > 0.0 ? 1 : -1); }

const char* cushion_name(int cushion) {
  switch (cushion) {
    case 0: return "y = 0";
    case 1: return "x = L";
    case 2: return "y = W";
    case 3: return "x = 0";
  }
  return "?";
}

}  // namespace

double shot_score(const problems::Problem& problem, const physics::ShotResult& result,
                  bool enforce_rigid_limit) {
  using physics::ShotStatus;
  const double miss = problem.has_target ? std::hypot(result.final_position.x - problem.target.x,
                                                      result.final_position.y - problem.target.y)
                                         : 0.0;
  double score = 0.0;
  switch (result.status) {
    case ShotStatus::rest: score = miss; break;
    case ShotStatus::pocketed:
    case ShotStatus::hit_obstacle: score = kEndedEarlyPenalty + miss; break;
    case ShotStatus::event_limit:
      // Cut short (the search caps events) after more cushions than allowed: scored as
      // at least one cushion more than it has met, from where it was.
      if (result.cushion_hits <= problem.limits.cushions_max) return kFailedPenalty;
      score = kCushionPenalty + miss;
      break;
    default: return kFailedPenalty;
  }
  if (!std::isfinite(score)) return kFailedPenalty;
  const problems::Limits& l = problem.limits;
  if (result.cushion_hits < l.cushions_min)
    score += kCushionPenalty * (l.cushions_min - result.cushion_hits);
  else if (result.cushion_hits > l.cushions_max)
    score += kCushionPenalty * (result.cushion_hits - l.cushions_max);
  const double rigid_limit = problem.scene.ball_and_cushion.rigid_speed_limit;
  if (enforce_rigid_limit && result.max_cushion_normal_speed > rigid_limit)
    score += kRigidPenalty + kRigidPenaltyPerSpeed * (result.max_cushion_normal_speed - rigid_limit);
  return score + pot_penalty(problem, result);
}

double pot_penalty(const problems::Problem& problem, const physics::ShotResult& result) {
  using problems::Failure;
  if (!problem.pot && !problem.first_contact) return 0.0;
  switch (problems::outcome_failure(problem, result)) {
    case Failure::first_contact: return 2.0 * kPotPenalty;
    case Failure::pot_missed:
    case Failure::wrong_pocket:
      // Nearer the pocket scores better, so that a pot too slow to drop is steered on.
      for (const physics::BallOutcome& b : result.balls)
        if (b.name == problem.pot->ball) {
          const physics::Vec2 c =
              problem.scene.pockets[static_cast<size_t>(problem.pot->pocket)].centre;
          return kPotPenalty + std::min(1.0, std::hypot(b.final_position.x - c.x,
                                                        b.final_position.y - c.y));
        }
      return 2.0 * kPotPenalty;
    case Failure::other_ball_pocketed: return kPotPenalty;
    default: return 0.0;
  }
}

int search_event_cap(const problems::Problem& problem, int max_events) {
  // Each object ball adds its own: struck, rolling, a cushion or two, a pocket or rest.
  const long cap = 3L * (problem.limits.cushions_max + 2) + 4 +
                   8L * static_cast<long>(problem.scene.balls.size());
  return static_cast<int>(std::min<long>(max_events, cap));
}

std::vector<int> route_of(const physics::ShotResult& result) {
  std::vector<int> route;
  for (const physics::ShotEvent& e : result.events)
    if (e.type == physics::EventType::cushion) route.push_back(e.cushion);
  return route;
}

FamilyKey family_key(const physics::Shot& shot, const physics::ShotResult& result) {
  FamilyKey key;
  key.route = route_of(result);
  key.topspin = sign_class(shot.topspin_k);
  key.sidespin = sign_class(shot.sidespin_k);
  key.ended_early = result.status != physics::ShotStatus::rest;
  return key;
}

}  // namespace detail

std::string describe(const Family& key) {
  std::string words;
  if (key.route.empty()) {
    words = "no cushion";
  } else {
    words = std::to_string(key.route.size()) + (key.route.size() == 1 ? " cushion (" : " cushions (");
    for (size_t i = 0; i < key.route.size(); ++i)
      words += std::string(i ? ", " : "") + detail::cushion_name(key.route[i]);
    words += ")";
  }
  words += key.topspin > 0 ? ", follow" : key.topspin < 0 ? ", draw" : ", stun";
  words += key.sidespin > 0 ? ", right spin" : key.sidespin < 0 ? ", left spin" : ", no side";
  return words;
}

namespace detail {

std::string violations(const problems::Problem& problem, const physics::Shot& shot,
                       const physics::ShotResult& result, bool enforce_rigid_limit) {
  std::string why;
  auto add = [&](const std::string& s) { why += (why.empty() ? "" : "; ") + s; };
  if (std::string s = problems::check_shot(problem.limits, shot); !s.empty()) add(s);
  switch (result.status) {
    case physics::ShotStatus::rest: break;
    case physics::ShotStatus::pocketed: add("the cue ball is pocketed"); break;
    case physics::ShotStatus::hit_obstacle: add("the cue ball touches an obstacle ball"); break;
    default:
      add(std::string("no outcome (") + physics::to_string(result.status) + "): " + result.message);
  }
  const problems::Limits& l = problem.limits;
  if (result.cushion_hits < l.cushions_min || result.cushion_hits > l.cushions_max)
    add(fmt::format("{} cushions, outside the allowed {}", result.cushion_hits, l.cushions_min) +
        (l.cushions_max != l.cushions_min ? fmt::format("-{}", l.cushions_max) : ""));
  // The pot's conditions, for a problem that has them.
  switch (const problems::Verdict v = problems::check_outcome(problem, result); v.failure) {
    case problems::Failure::first_contact:
    case problems::Failure::pot_missed:
    case problems::Failure::wrong_pocket:
    case problems::Failure::other_ball_pocketed: add(v.reason); break;
    default: break;
  }
  const double rigid_limit = problem.scene.ball_and_cushion.rigid_speed_limit;
  if (enforce_rigid_limit && result.max_cushion_normal_speed > rigid_limit)
    add(fmt::format("cushion normal speed {:.3g} m/s above the rigid-cushion limit {:.3g} m/s",
                    result.max_cushion_normal_speed, rigid_limit));
  return why;
}

}  // namespace detail

namespace detail {

PlannedShot describe_outcome(const problems::Problem& problem, const physics::Shot& shot,
                             const physics::ShotResult& r, bool enforce_rigid_limit) {
  PlannedShot p;
  p.shot = shot;
  p.outcome = r.status;
  p.final_position = r.final_position;
  p.miss_distance = problems::miss_distance(problem, r);
  p.cushion_hits = r.cushion_hits;
  p.route = route_of(r);
  const problems::Limits& l = problem.limits;
  p.within_limits = problems::check_shot(l, shot).empty() && r.cushion_hits >= l.cushions_min &&
                    r.cushion_hits <= l.cushions_max;
  p.rigid_limit_exceeded = r.rigid_limit_exceeded ||
                          r.max_cushion_normal_speed > problem.scene.ball_and_cushion.rigid_speed_limit;
  p.max_cushion_normal_speed = r.max_cushion_normal_speed;
  p.family_key = family_key(shot, r);
  p.family = describe(p.family_key);
  p.impact_method = r.impact_method;
  p.violations = violations(problem, shot, r, enforce_rigid_limit);
  const problems::Verdict verdict = problems::check_stroke(problem, shot, r);
  p.failure = verdict.failure;
  p.failure_reason = verdict.reason;
  p.solves = p.violations.empty() && verdict.solves();
  return p;
}

}  // namespace detail

PlannedShot evaluate(const problems::Problem& problem, const physics::Shot& shot,
                     const physics::SimulationOptions& simulation) {
  physics::SimulationOptions quiet = simulation;
  quiet.record_path = false;
  const physics::ShotResult r = physics::simulate(problem.scene, problem.cue_ball, shot, quiet);
  return detail::describe_outcome(problem, shot, r, /*enforce_rigid_limit=*/false);
}

}  // namespace cueplan::planner
