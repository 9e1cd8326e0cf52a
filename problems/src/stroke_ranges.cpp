#include "cueplan/problems/stroke_ranges.hpp"

#include <fmt/format.h>

#include <cmath>

namespace cueplan::problems {
namespace {

void refuse(StrokeRangeCheck& c, const char* name, std::string message) {
  if (!c.error.empty()) return;
  c.field = name;
  c.error = std::string(name) + " " + std::move(message);
}

void speed_into(StrokeRangeCheck& c, double speed, const char* name) {
  if (name == nullptr) return;
  if (!std::isfinite(speed) || !(speed > 0.0)) {
    refuse(c, name, fmt::format("must be above 0 and finite (m/s), got {}", speed));
  } else if (speed > kMaxStrokeSpeed) {
    refuse(c, name,
           fmt::format("must be at most {:g} m/s: no cue gives a cue ball more (the fastest "
                       "breaks are about 14 m/s), got {:g}",
                       kMaxStrokeSpeed, speed));
  } else if (speed > kBreakShotSpeed) {
    c.warnings.push_back(fmt::format("{} {:g} m/s is faster than a break shot (about {:g} m/s); "
                                     "few players can play it",
                                     name, speed, kBreakShotSpeed));
  }
}

// `what` leads the message after the name: "= 3" or "1 with stroke.sidespin_k 2 gives
// spin sqrt(k_T^2 + k_S^2) = 2.24".
void spin_into(StrokeRangeCheck& c, double spin, const char* name, const std::string& what) {
  if (!std::isfinite(spin)) {
    refuse(c, name, fmt::format("must be finite, got {}", spin));
  } else if (spin > physics::kMiscueSpin * (1 + 1e-12)) {
    refuse(c, name,
           fmt::format("{}: that puts the cue's tip {:.2f} ball radii from the ball's centre "
                       "(tip offset = spin / {:g}); beyond half a radius (spin {:g}) the cue "
                       "miscues",
                       what, spin / physics::kSpinPerTipOffset, physics::kSpinPerTipOffset,
                       physics::kMiscueSpin));
  }
}

}  // namespace

std::vector<std::string> problem_warnings(const Problem& problem) {
  return check_speed_range(problem.limits.speed_max, "limits.speed[1]").warnings;
}

StrokeRangeCheck check_speed_range(double speed, const char* name) {
  StrokeRangeCheck c;
  speed_into(c, speed, name);
  return c;
}

StrokeRangeCheck check_spin_range(double spin, const char* name) {
  StrokeRangeCheck c;
  if (std::isfinite(spin) && spin < 0.0)
    refuse(c, name, fmt::format("must not be negative, got {:g}", spin));
  spin_into(c, spin, name, fmt::format("= {:g}", spin));
  return c;
}

StrokeRangeCheck check_stroke_ranges(const physics::Shot& shot, const StrokeFieldNames& names,
                                     std::optional<double> elevation_deg) {
  StrokeRangeCheck c;
  speed_into(c, shot.speed, names.speed);
  if (names.aim != nullptr) {
    if (!std::isfinite(shot.aim_deg) || std::abs(shot.aim_deg) > kMaxAimDeg)
      refuse(c, names.aim,
             fmt::format("must be an angle from {:g} to {:g} deg, got {}", -kMaxAimDeg,
                         kMaxAimDeg, shot.aim_deg));
  }
  if (names.topspin != nullptr && !std::isfinite(shot.topspin_k))
    refuse(c, names.topspin, fmt::format("must be finite, got {}", shot.topspin_k));
  if (names.sidespin != nullptr && !std::isfinite(shot.sidespin_k))
    refuse(c, names.sidespin, fmt::format("must be finite, got {}", shot.sidespin_k));
  if (names.topspin != nullptr && names.sidespin != nullptr && c.error.empty()) {
    const double spin = std::hypot(shot.topspin_k, shot.sidespin_k);
    // The field named is the larger part of the spin.
    const bool top = std::abs(shot.topspin_k) >= std::abs(shot.sidespin_k);
    spin_into(c, spin, top ? names.topspin : names.sidespin,
              fmt::format("{:g} with {} {:g} gives spin sqrt(k_T^2 + k_S^2) = {:g}",
                          top ? shot.topspin_k : shot.sidespin_k,
                          top ? names.sidespin : names.topspin,
                          top ? shot.sidespin_k : shot.topspin_k, spin));
  }
  if (names.elevation != nullptr && elevation_deg) {
    const double e = *elevation_deg;
    if (!std::isfinite(e) || e < 0.0 || e > kMaxElevationDeg)
      refuse(c, names.elevation,
             fmt::format("must be 0 to {:g} deg (the cue's tilt above the cloth), got {}",
                         kMaxElevationDeg, e));
  }
  return c;
}

}  // namespace cueplan::problems
