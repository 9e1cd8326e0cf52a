// Problems in an obstacle field: the target is where a random stroke stops after
// threading between balls, in a scene where most nearby strokes do not.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "cueplan/planner/planner.hpp"
#include "robustness.hpp"
#include "search_space.hpp"

namespace cueplan::planner {

std::vector<KnownShotProblem> obstacle_field_problems(int count, int obstacles, uint64_t seed,
                                                      const physics::SimulationOptions& simulation) {
  constexpr double kSpeedMin = 0.3, kSpeedMax = 3.0;  // m/s
  constexpr int kMaxCushions = 3;
  constexpr double kMargin = 0.1;      // m, balls kept this far inside the cushion noses
  constexpr double kBallGap = 0.01;    // m, free space kept between any two balls
  constexpr int kNearStrokes = 32;     // strokes near the witness, to judge the gap
  constexpr double kNearAimDeg = 3.0, kNearSpeed = 0.15, kNearSpin = 0.3;
  constexpr double kMinBlocked = 0.25;  // fraction of them that must end on a ball or pocket
  std::vector<KnownShotProblem> out;
  if (count <= 0) return out;
  obstacles = std::clamp(obstacles, 1, 30);
  std::mt19937_64 rng(detail::stream_seed(seed, 0x6669656c64ULL));  // "field"
  auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
  };
  physics::SimulationOptions sim = simulation;
  sim.record_path = false;
  problems::Problem base;
  base.scene = physics::snooker_scene();
  base.source = "<generated>";
  base.tolerance = problems::kDefaultTolerance;
  const double clearance = 2.0 * base.scene.radius() + kBallGap;
  // A free spot for a ball: inside the margin, out of the pockets, clear of the others.
  auto free_spot = [&](const physics::Scene& scene, physics::Vec2* spot) {
    for (int attempt = 0; attempt < 1000; ++attempt) {
      const physics::Vec2 p{uniform(kMargin, scene.length - kMargin), uniform(kMargin, scene.width - kMargin)};
      if (!scene.check_position(p, "ball").empty()) continue;
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
    p.target = r.final_position;
    p.limits.cushions_min = p.limits.cushions_max = r.cushion_hits;
    p.name = "obstacle field " + std::to_string(out.size() + 1);
    out.push_back({std::move(p), shot});
  }
  return out;
}

}  // namespace cueplan::planner
