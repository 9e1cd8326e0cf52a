// Problems whose answer is known: the target is where a random stroke stops.
#include <string>

#include "cueplan/planner/planner.hpp"
#include "generated_problems.hpp"
#include "robustness.hpp"
#include "search_space.hpp"

namespace cueplan::planner {

namespace detail {

problems::Problem generated_base() {
  problems::Problem base;
  base.scene = physics::snooker_scene();
  base.source = "<generated>";
  base.tolerance = problems::kDefaultTolerance;
  return base;
}

physics::Shot random_stroke(UniformStream& uniform, double spin_max) {
  physics::Shot shot;
  shot.speed = uniform(kGeneratedSpeedMin, kGeneratedSpeedMax);
  shot.aim_deg = uniform(-180.0, 180.0);
  double side, top;  // uniform over the spin disc
  square_to_disc(uniform(-1.0, 1.0), uniform(-1.0, 1.0), &side, &top);
  shot.sidespin_k = spin_max * side;
  shot.topspin_k = spin_max * top;
  return shot;
}

bool take_landing_as_target(const physics::ShotResult& result, problems::Problem* problem) {
  if (result.status != physics::ShotStatus::rest || result.cushion_hits > kGeneratedMaxCushions)
    return false;
  if (problem->scene.check_position(result.final_position, {"target"})) return false;
  problem->target = result.final_position;
  problem->limits.cushions_min = problem->limits.cushions_max = result.cushion_hits;
  return true;
}

}  // namespace detail

std::vector<KnownShotProblem> known_shot_problems(int count, uint64_t seed,
                                                  const physics::SimulationOptions& simulation) {
  std::vector<KnownShotProblem> out;
  detail::UniformStream uniform(detail::stream_seed(seed, 0x6b6e6f776eULL));  // "known"
  physics::SimulationOptions sim = simulation;
  sim.record_path = false;
  const problems::Problem base = detail::generated_base();
  constexpr double kMargin = detail::kGeneratedMargin;
  while (static_cast<int>(out.size()) < count) {
    problems::Problem p = base;
    p.cue_ball = {uniform(kMargin, p.scene.length - kMargin), uniform(kMargin, p.scene.width - kMargin)};
    if (p.scene.check_position(p.cue_ball, {"cue_ball"})) continue;
    const physics::Shot shot = detail::random_stroke(uniform, p.limits.spin_max);
    const physics::ShotResult r = physics::simulate(p.scene, p.cue_ball, shot, sim);
    if (!detail::take_landing_as_target(r, &p)) continue;
    p.name = "known shot " + std::to_string(out.size() + 1);
    out.push_back({std::move(p), shot});
  }
  return out;
}

}  // namespace cueplan::planner
