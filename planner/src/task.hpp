// A problem as the planner's hot paths take it: checked once (problems::validate) and
// its scene compiled, so the thousands of simulations that follow check nothing again.
#pragma once

#include <memory>
#include <optional>

#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/position.hpp"
#include "cueplan/problems/problem.hpp"
#include "pot_aim.hpp"

namespace cueplan::planner::detail {

struct Task {
  // `checked` must outlive the task; it is checked by the caller (plan(), plan_route(),
  // spin_map() run problems::validate before anything else).
  // `solve_pot_aim`: a pot problem's aim is solved (pot_aim), not searched.
  explicit Task(const problems::Problem& checked, bool solve_pot_aim = true)
      : problem(checked), scene(checked.scene) {
    if (checked.pot && solve_pot_aim) pot_aim.emplace(checked);
  }

  // A stroke from the problem's cue ball.
  physics::ShotResult simulate(const physics::Shot& shot,
                               const physics::SimulationOptions& options) const {
    return physics::simulate(scene, problem.cue_ball, shot, options);
  }
  // A stroke from somewhere else on the table (a route's later strokes).
  physics::ShotResult simulate_from(physics::Vec2 cue_ball, const physics::Shot& shot,
                                    const physics::SimulationOptions& options) const {
    return physics::simulate(scene, cue_ball, shot, options);
  }
  double rigid_limit() const { return problem.scene.ball_and_cushion.rigid_speed_limit; }

  const problems::Problem& problem;
  const physics::CompiledScene scene;
  // A pot problem's aim solver (the aim is solved, not searched); empty without a pot.
  std::optional<PotAim> pot_aim;
  // Position play (problem.next): the field the landings are judged by; null without
  // a next pot (set by the planner after construction, from its cache).
  std::shared_ptr<const PositionField> next_field;

  // The position term of the nominal score: for a problem with a next pot and no target,
  // kNextScale x (1 - value / best value) at the landing (m, as the miss distance it
  // stands for; below the pot's penalty, so a pot always scores better than a miss), so
  // that the search steers the cue ball toward the zone as it steers it toward a target.
  static constexpr double kNextScale = 0.25;  // m
  // The nominal score at or below which a stroke does what the problem asks (the target's
  // tolerance; with position play and no target, any pot: below kNextScale plus a hair).
  double landing_score() const {
    return next_field && !problem.has_target ? kNextScale + 1e-9 : problem.tolerance;
  }
  double next_score(const physics::ShotResult& result) const {
    if (!next_field || problem.has_target || result.status != physics::ShotStatus::rest) return 0.0;
    const double best = next_field->best_value();
    if (!(best > 0.0)) return 0.0;
    return kNextScale * (1.0 - std::min(1.0, next_field->value(result.final_position) / best));
  }
};

}  // namespace cueplan::planner::detail
