// A problem as the planner's hot paths take it: checked once (problems::validate) and
// its scene compiled, so the thousands of simulations that follow check nothing again.
#pragma once

#include <optional>

#include "cueplan/physics/shot.hpp"
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
};

}  // namespace cueplan::planner::detail
