// The unit cube of the search and the strokes it stands for.
#include "search_space.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cueplan::planner::detail {
namespace {

constexpr double kQuarterPi = std::numbers::pi / 4.0;

double clamp01(double u) { return std::isfinite(u) ? std::clamp(u, 0.0, 1.0) : 0.5; }

}  // namespace

// Concentric map: each square ring |a| or |b| = r goes onto the circle of radius r,
// its four sides onto four quarter arcs, keeping area ratios (Shirley & Chiu 1997).
void square_to_disc(double a, double b, double* x, double* y) {
  if (a == 0.0 && b == 0.0) {
    *x = *y = 0.0;
    return;
  }
  double r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    phi = kQuarterPi * (b / a);
  } else {
    r = b;
    phi = 2.0 * kQuarterPi - kQuarterPi * (a / b);
  }
  *x = r * std::cos(phi);
  *y = r * std::sin(phi);
}

void disc_to_square(double x, double y, double* a, double* b) {
  const double r = std::hypot(x, y);
  if (r == 0.0) {
    *a = *b = 0.0;
    return;
  }
  double phi = std::atan2(y, x);  // (-pi, pi]
  if (phi < -kQuarterPi) phi += 2.0 * std::numbers::pi;  // [-pi/4, 7pi/4)
  if (phi < kQuarterPi) {
    *a = r;
    *b = phi / kQuarterPi * r;
  } else if (phi < 3.0 * kQuarterPi) {
    *b = r;
    *a = -(phi - 2.0 * kQuarterPi) / kQuarterPi * r;
  } else if (phi < 5.0 * kQuarterPi) {
    *a = -r;
    *b = (phi - 4.0 * kQuarterPi) / kQuarterPi * *a;
  } else {
    *b = -r;
    *a = -(phi - 6.0 * kQuarterPi) / kQuarterPi * *b;
  }
}

double wrap_degrees(double deg) {
  double w = std::fmod(deg + 180.0, 360.0);
  if (w < 0.0) w += 360.0;
  w -= 180.0;
  return w >= 180.0 ? w - 360.0 : w;
}

SearchSpace::SearchSpace(const problems::Limits& limits, double aim_centre_deg,
                         std::optional<double> held_sidespin_k, bool aim_solved)
    : limits_(limits), held_sidespin_(held_sidespin_k) {
  if (held_sidespin_) {
    held_sidespin_ = std::clamp(*held_sidespin_, -limits.spin_max, limits.spin_max);
    topspin_reach_ = std::sqrt(std::max(
        0.0, limits.spin_max * limits.spin_max - *held_sidespin_ * *held_sidespin_));
  }
  switch (limits.aim.mode) {
    case problems::AimMode::free:
      aim_lo_ = aim_centre_deg - 180.0;
      aim_hi_ = aim_centre_deg + 180.0;
      break;
    case problems::AimMode::fixed:
      aim_lo_ = aim_hi_ = limits.aim.lo_deg;
      aim_searched_ = false;
      break;
    case problems::AimMode::range:
      aim_lo_ = limits.aim.lo_deg;
      aim_hi_ = limits.aim.hi_deg;
      break;
  }
  if (aim_solved) {
    aim_lo_ = aim_hi_ = 0.0;
    aim_searched_ = false;
    aim_solved_ = true;
  }
}

physics::Shot SearchSpace::shot(const double* u) const {
  physics::Shot s;
  // The elevation is not searched: the least the limits allow (a level cue by default).
  s.elevation_deg = limits_.elevation_min_deg;
  int i = 0;
  s.speed = limits_.speed_min + clamp01(u[i++]) * (limits_.speed_max - limits_.speed_min);
  if (aim_searched_) {
    s.aim_deg = aim_lo_ + clamp01(u[i++]) * (aim_hi_ - aim_lo_);
    if (limits_.aim.mode == problems::AimMode::free) s.aim_deg = wrap_degrees(s.aim_deg);
  } else {
    s.aim_deg = aim_lo_;
  }
  if (held_sidespin_) {
    s.sidespin_k = *held_sidespin_;
    s.topspin_k = topspin_reach_ * (2.0 * clamp01(u[i]) - 1.0);
    return s;
  }
  double side, top;
  square_to_disc(2.0 * clamp01(u[i]) - 1.0, 2.0 * clamp01(u[i + 1]) - 1.0, &side, &top);
  s.sidespin_k = limits_.spin_max * side;
  s.topspin_k = limits_.spin_max * top;
  return s;
}

double SearchSpace::pot_offset(const double* u) const {
  return aim_solved_ ? 2.0 * clamp01(u[dimension() - 1]) - 1.0 : 0.0;
}

std::vector<double> SearchSpace::point(const physics::Shot& shot, double pot_offset) const {
  std::vector<double> u;
  u.push_back(clamp01((shot.speed - limits_.speed_min) / (limits_.speed_max - limits_.speed_min)));
  if (aim_searched_) {
    double aim = shot.aim_deg;
    // Bring the aim into [lo, lo + 360) before placing it in the searched interval.
    aim = aim_lo_ + (wrap_degrees(aim - aim_lo_ - 180.0) + 180.0);
    u.push_back(clamp01((aim - aim_lo_) / (aim_hi_ - aim_lo_)));
  }
  if (held_sidespin_) {
    const double t = topspin_reach_ > 0.0 ? shot.topspin_k / topspin_reach_ : 0.0;
    u.push_back(clamp01(0.5 * (t + 1.0)));
    if (aim_solved_) u.push_back(clamp01(0.5 * (pot_offset + 1.0)));
    return u;
  }
  double a, b;
  const double r = std::hypot(shot.sidespin_k, shot.topspin_k);
  const double shrink = r > limits_.spin_max ? limits_.spin_max / r : 1.0;
  disc_to_square(shrink * shot.sidespin_k / limits_.spin_max,
                 shrink * shot.topspin_k / limits_.spin_max, &a, &b);
  u.push_back(clamp01(0.5 * (a + 1.0)));
  u.push_back(clamp01(0.5 * (b + 1.0)));
  if (aim_solved_) u.push_back(clamp01(0.5 * (pot_offset + 1.0)));
  return u;
}

}  // namespace cueplan::planner::detail
