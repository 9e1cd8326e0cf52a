// A problem as the planner's hot paths take it: checked once (problems::validate) and
// its scene compiled, so the thousands of simulations that follow check nothing again.
#pragma once

#include <cmath>
#include <memory>
#include <optional>
#include <vector>

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
  // The standard deviation of the stroke's speed (m/s; NoiseModel::speed x scale) that
  // landing_worth() spreads the landing by; 0 judges the landing alone.
  double landing_speed_sd = 0.0;
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

  // A landing's worth with a stroke's spread around it: the field's value where the
  // cue ball stops, averaged (weights 2, 1, 1, 1, 1) with four points where a player's
  // stroke also leaves it - one speed error (landing_speed_sd) further and shorter
  // along its last line of travel, and as far to either side. The field is flat (a
  // sure pot) over whole zones, so the landing alone cannot tell a zone's middle from
  // its edge, where half the noisy strokes stop outside. A rolling ball's distance
  // grows with the square of its speed, so a relative speed error e moves the landing
  // by about 2 e of the distance the cue ball runs after it first meets a ball (from
  // the strike, when it meets none). The planner ranks the position grid's strokes by it.
  double landing_worth(const physics::ShotResult& result) const {
    const physics::Vec2 end = result.final_position;
    const double here = next_field->value(end);
    const std::vector<physics::ShotEvent>& events = result.events;
    if (!(landing_speed_sd > 0.0) || events.size() < 2) return here;
    const double strike_speed = std::hypot(events.front().velocity.x, events.front().velocity.y);
    if (!(strike_speed > 0.0)) return here;
    size_t from = 0;
    for (size_t i = 0; i < events.size(); ++i)
      if (events[i].type == physics::EventType::ball_contact) {
        from = i;
        break;
      }
    double run = 0.0;
    physics::Vec2 last_direction{0.0, 0.0};
    for (size_t i = from; i + 1 < events.size(); ++i) {
      const double dx = events[i + 1].position.x - events[i].position.x;
      const double dy = events[i + 1].position.y - events[i].position.y;
      const double d = std::hypot(dx, dy);
      run += d;
      if (d > 1e-6) last_direction = {dx / d, dy / d};
    }
    const double spread = std::min(kMostSpread, 2.0 * landing_speed_sd / strike_speed * run);
    if (!(spread > 1e-4) || (last_direction.x == 0.0 && last_direction.y == 0.0)) return here;
    const physics::Vec2 a{spread * last_direction.x, spread * last_direction.y};
    const physics::Vec2 c{-a.y, a.x};
    double sum = 2.0 * here;
    for (const physics::Vec2 d : {a, c})
      for (const double sign : {1.0, -1.0})
        sum += next_field->value({end.x + sign * d.x, end.y + sign * d.y});
    return sum / 6.0;
  }
  static constexpr double kMostSpread = 0.3;  // m
};

}  // namespace cueplan::planner::detail
