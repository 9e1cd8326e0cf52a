// What a problem asks for: a human summary, and the tests a shot and its outcome pass.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "cueplan/problems/problem.hpp"

namespace cueplan::problems {
namespace {

// printf into a std::string; every use here is short.
template <typename... Args>
std::string format(const char* pattern, Args... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, pattern, args...);
  return buf;
}

// True when `phi` lies in [lo, hi] (deg) up to whole turns.
bool aim_within(double phi, double lo, double hi) {
  constexpr double kSlack = 1e-9;  // deg
  const double turns = std::floor((phi - lo) / 360.0);
  const double shifted = phi - 360.0 * turns;  // in [lo, lo + 360)
  return shifted <= hi + kSlack || shifted >= lo + 360.0 - kSlack;
}

std::string describe_aim(const AimLimit& aim) {
  switch (aim.mode) {
    case AimMode::free: return "aim free";
    case AimMode::fixed: return format("aim %.6g deg", aim.lo_deg);
    case AimMode::range: return format("aim %.6g to %.6g deg", aim.lo_deg, aim.hi_deg);
  }
  return "aim ?";
}

}  // namespace

std::string describe(const Problem& p) {
  const physics::Scene& s = p.scene;
  const physics::CushionParams& b = s.ball_and_cushion;
  std::string text = p.name + "  (" + p.source + ")\n";
  text += format("  table %.4g x %.4g m, ", s.length, s.width);
  text += s.pockets.empty() ? std::string("no pockets")
                            : format("%zu pockets (capture radius %.4g mm)", s.pockets.size(),
                                     1e3 * s.pockets.front().radius);
  text += format("; ball R %.5g mm, %.4g g\n", 1e3 * b.radius, 1e3 * b.mass);
  text += format(
      "  cloth mu_s %.4g, mu_r %.4g, mu_sp %.4g, g %.4g m/s^2; cushion mu_w %.4g, e %.4g, "
      "h %.5g mm\n",
      s.cloth.mu_slide, s.cloth.mu_roll, s.cloth.mu_spin, s.cloth.gravity, b.mu_cushion,
      b.restitution, 1e3 * b.cushion_height);
  text += format("  cue ball (%.4f, %.4f) m -> target (%.4f, %.4f) m within %.4g mm", p.cue_ball.x,
                 p.cue_ball.y, p.target.x, p.target.y, 1e3 * p.tolerance);
  if (!s.obstacles.empty())
    text += format("; %zu obstacle%s", s.obstacles.size(), s.obstacles.size() == 1 ? "" : "s");
  const Limits& l = p.limits;
  text += format("\n  limits: speed %.4g-%.4g m/s, spin <= %.4g, %s, ", l.speed_min, l.speed_max,
                 l.spin_max, describe_aim(l.aim).c_str());
  text += l.cushions_min == l.cushions_max
              ? format("%d cushion%s", l.cushions_min, l.cushions_min == 1 ? "" : "s")
              : format("%d-%d cushions", l.cushions_min, l.cushions_max);
  return text + "\n";
}

std::string check_shot(const Limits& limits, const physics::Shot& shot) {
  constexpr double kSlack = 1e-12;  // relative, so bounds written in the file are inside
  if (!std::isfinite(shot.speed) || shot.speed < limits.speed_min * (1 - kSlack) ||
      shot.speed > limits.speed_max * (1 + kSlack))
    return format("speed %.6g m/s lies outside [%.6g, %.6g] m/s", shot.speed, limits.speed_min,
                  limits.speed_max);
  const double spin = std::hypot(shot.topspin_k, shot.sidespin_k);
  if (!std::isfinite(spin) || spin > limits.spin_max * (1 + kSlack))
    return format("spin sqrt(k_T^2 + k_S^2) = %.6g exceeds %.6g", spin, limits.spin_max);
  const AimLimit& aim = limits.aim;
  if (!std::isfinite(shot.aim_deg))
    return "aim must be finite";
  if (aim.mode != AimMode::free && !aim_within(shot.aim_deg, aim.lo_deg, aim.hi_deg))
    return format("aim %.6g deg lies outside [%.6g, %.6g] deg", shot.aim_deg, aim.lo_deg,
                  aim.hi_deg);
  return {};
}

double miss_distance(const Problem& problem, const physics::ShotResult& result) {
  if (result.status != physics::ShotStatus::rest)
    return std::numeric_limits<double>::infinity();
  return std::hypot(result.final_position.x - problem.target.x,
                    result.final_position.y - problem.target.y);
}

bool reaches_target(const Problem& problem, const physics::ShotResult& result) {
  return miss_distance(problem, result) <= problem.tolerance &&
         result.cushion_hits >= problem.limits.cushions_min &&
         result.cushion_hits <= problem.limits.cushions_max;
}

}  // namespace cueplan::problems
