// Problems whose answer is known: the target is where a random stroke stops.
#include <random>
#include <string>

#include "cueplan/planner/planner.hpp"
#include "robustness.hpp"
#include "search_space.hpp"

namespace cueplan::planner {

std::vector<KnownShotProblem> known_shot_problems(int count, uint64_t seed,
                                                  const physics::SimulationOptions& simulation) {
  constexpr double kSpeedMin = 0.3, kSpeedMax = 3.0;  // m/s
  constexpr int kMaxCushions = 3;
  constexpr double kMargin = 0.1;  // m, cue ball kept this far inside the cushion noses
  std::vector<KnownShotProblem> out;
  std::mt19937_64 rng(detail::stream_seed(seed, 0x6b6e6f776eULL));  // "known"
  auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
  };
  physics::SimulationOptions sim = simulation;
  sim.record_path = false;
  problems::Problem base;
  base.scene = physics::snooker_scene();
  base.source = "<generated>";
  base.tolerance = problems::kDefaultTolerance;
  while (static_cast<int>(out.size()) < count) {
    problems::Problem p = base;
    p.cue_ball = {uniform(kMargin, p.scene.length - kMargin), uniform(kMargin, p.scene.width - kMargin)};
    if (!p.scene.check_position(p.cue_ball, "cue_ball").empty()) continue;
    physics::Shot shot;
    shot.speed = uniform(kSpeedMin, kSpeedMax);
    shot.aim_deg = uniform(-180.0, 180.0);
    double side, top;  // uniform over the spin disc
    detail::square_to_disc(uniform(-1.0, 1.0), uniform(-1.0, 1.0), &side, &top);
    shot.sidespin_k = p.limits.spin_max * side;
    shot.topspin_k = p.limits.spin_max * top;
    const physics::ShotResult r = physics::simulate(p.scene, p.cue_ball, shot, sim);
    if (r.status != physics::ShotStatus::rest || r.cushion_hits > kMaxCushions) continue;
    if (!p.scene.check_position(r.final_position, "target").empty()) continue;
    p.target = r.final_position;
    p.limits.cushions_min = p.limits.cushions_max = r.cushion_hits;
    p.name = "known shot " + std::to_string(out.size() + 1);
    out.push_back({std::move(p), shot});
  }
  return out;
}

}  // namespace cueplan::planner
