// Pot problems whose answer is known: a random stroke at a random object ball that pots
// it cleanly; the pocket it drops in is the pot, where the cue ball stops the target.
#include <cmath>
#include <numbers>
#include <string>

#include "cueplan/planner/planner.hpp"
#include "generated_problems.hpp"
#include "robustness.hpp"
#include "search_space.hpp"

namespace cueplan::planner {

std::vector<KnownShotProblem> known_pot_problems(int count, uint64_t seed,
                                                 const physics::SimulationOptions& simulation) {
  std::vector<KnownShotProblem> out;
  detail::UniformStream uniform(detail::stream_seed(seed, 0x706f74ULL));  // "pot"
  physics::SimulationOptions sim = simulation;
  sim.record_path = false;
  const problems::Problem base = detail::generated_base();
  constexpr double kMargin = detail::kGeneratedMargin;
  constexpr double kDeg = 180.0 / std::numbers::pi;
  while (static_cast<int>(out.size()) < count) {
    problems::Problem p = base;
    const physics::Scene& s = p.scene;
    const physics::Vec2 red{uniform(kMargin, s.length - kMargin), uniform(kMargin, s.width - kMargin)};
    p.scene.balls = {{"red", red}};
    p.cue_ball = {uniform(kMargin, s.length - kMargin), uniform(kMargin, s.width - kMargin)};
    if (p.scene.validate() || p.scene.check_position(p.cue_ball, {"cue_ball"})) continue;
    // Aimed to strike the red: its direction plus an offset within 90 % of a half-ball
    // either side (cuts up to about 64 degrees).
    const double dx = red.x - p.cue_ball.x, dy = red.y - p.cue_ball.y;
    const double distance = std::hypot(dx, dy);
    const double reach = std::asin(std::min(1.0, 0.9 * 2.0 * s.radius() / distance)) * kDeg;
    physics::Shot shot = detail::random_stroke(uniform, p.limits.spin_max);
    shot.aim_deg = detail::wrap_degrees(std::atan2(dy, dx) * kDeg + uniform(-reach, reach));
    const physics::ShotResult r = physics::simulate(p.scene, p.cue_ball, shot, sim);
    if (r.balls.size() < 2 || !r.balls[1].pocketed) continue;
    // A direct pot, as the planner plans them: the red goes straight in, meeting no
    // cushion or ball after the cue ball's (banks and kisses are not planned).
    bool direct = true;
    for (size_t i = 1; i < r.balls[1].events.size(); ++i) {
      const physics::EventType t = r.balls[1].events[i].type;
      direct = direct && t != physics::EventType::cushion && t != physics::EventType::ball_contact;
    }
    if (!direct || r.first_contact != 1) continue;
    p.pot = problems::Pot{"red", r.balls[1].pocket};
    p.limits.cushions_min = 0;  // a pot problem's default cushions, [0, 3]
    p.limits.cushions_max = detail::kGeneratedMaxCushions;
    if (r.status != physics::ShotStatus::rest || r.cushion_hits > p.limits.cushions_max ||
        p.scene.check_rest_position(r.final_position, {"target"}))
      continue;
    p.target = r.final_position;
    if (!problems::check_stroke(p, shot, r).solves() || problems::validate(p)) continue;
    p.name = "known pot " + std::to_string(out.size() + 1);
    out.push_back({std::move(p), shot});
  }
  return out;
}

}  // namespace cueplan::planner
