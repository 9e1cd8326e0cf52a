// Problems in an obstacle field: the target is where a random stroke stops after
// threading between balls, in a scene where most nearby strokes do not.
#include <algorithm>
#include <cmath>
#include <string>

#include "cueplan/planner/planner.hpp"
#include "generated_problems.hpp"
#include "robustness.hpp"
#include "search_space.hpp"

namespace cueplan::planner {

std::vector<KnownShotProblem> obstacle_field_problems(int count, int obstacles, uint64_t seed,
                                                      const physics::SimulationOptions& simulation) {
  constexpr double kSpeedMin = detail::kGeneratedSpeedMin, kSpeedMax = detail::kGeneratedSpeedMax;
  constexpr double kMargin = detail::kGeneratedMargin;
  constexpr double kBallGap = 0.01;    // m, free space kept between any two balls
  constexpr int kNearStrokes = 32;     // strokes near the witness, to judge the gap
  constexpr double kNearAimDeg = 3.0, kNearSpeed = 0.15, kNearSpin = 0.3;
  constexpr double kMinBlocked = 0.25;  // fraction of them that must end on a ball or pocket
  std::vector<KnownShotProblem> out;
  if (count <= 0) return out;
  obstacles = std::clamp(obstacles, 1, 30);
  detail::UniformStream uniform(detail::stream_seed(seed, 0x6669656c64ULL));  // "field"
  physics::SimulationOptions sim = simulation;
  sim.record_path = false;
  const problems::Problem base = detail::generated_base();
  const double clearance = 2.0 * base.scene.radius() + kBallGap;
  // A free spot for a ball: inside the margin, out of the pockets, clear of the others.
  auto free_spot = [&](const physics::Scene& scene, physics::Vec2* spot) {
    for (int attempt = 0; attempt < 1000; ++attempt) {
      const physics::Vec2 p{uniform(kMargin, scene.length - kMargin), uniform(kMargin, scene.width - kMargin)};
      if (scene.check_position(p, {"ball"})) continue;
      bool clear = true;
      for (const physics::Vec2& o : scene.obstacles) clear = clear && std::hypot(p.x - o.x, p.y - o.y) >= clearance;
      if (!clear) continue;
      *spot = p;
      return true;
    }
    return false;
  };
  auto ended_on_ball_or_pocket = [](const physics::ShotResult& r) {
    return r.status == physics::ShotStatus::hit_obstacle || r.status == physics::ShotStatus::pocketed;
  };
  while (static_cast<int>(out.size()) < count) {
    problems::Problem p = base;
    bool placed = true;
    for (int i = 0; i < obstacles && placed; ++i) {
      physics::Vec2 spot;
      placed = free_spot(p.scene, &spot);
      if (placed) p.scene.obstacles.push_back(spot);
    }
    if (!placed || !free_spot(p.scene, &p.cue_ball)) continue;
    const physics::Shot shot = detail::random_stroke(uniform, p.limits.spin_max);
    const physics::ShotResult r = physics::simulate(p.scene, p.cue_ball, shot, sim);
    if (!detail::take_landing_as_target(r, &p)) continue;
    // Keep the scene only when the witness threads a narrow gap.
    int blocked = 0;
    for (int i = 0; i < kNearStrokes; ++i) {
      physics::Shot near = shot;
      near.aim_deg = detail::wrap_degrees(shot.aim_deg + uniform(-kNearAimDeg, kNearAimDeg));
      near.speed = std::clamp(shot.speed * (1.0 + uniform(-kNearSpeed, kNearSpeed)), kSpeedMin, kSpeedMax);
      near.topspin_k = shot.topspin_k + uniform(-kNearSpin, kNearSpin);
      near.sidespin_k = shot.sidespin_k + uniform(-kNearSpin, kNearSpin);
      const double k = std::hypot(near.topspin_k, near.sidespin_k);
      if (k > p.limits.spin_max) {
        near.topspin_k *= p.limits.spin_max / k;
        near.sidespin_k *= p.limits.spin_max / k;
      }
      if (ended_on_ball_or_pocket(physics::simulate(p.scene, p.cue_ball, near, sim))) ++blocked;
    }
    if (blocked < kMinBlocked * kNearStrokes) continue;
    p.name = "obstacle field " + std::to_string(out.size() + 1);
    out.push_back({std::move(p), shot});
  }
  return out;
}

}  // namespace cueplan::planner
