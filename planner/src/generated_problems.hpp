// What the generators of problems with a known answer (known_shot_problems,
// obstacle_field_problems) share: a seeded uniform stream, the generated problem's
// starting point, a random stroke within the default limits, and the check that turns
// a stroke's outcome into the problem's target.
#pragma once

#include <cstdint>
#include <random>

#include "cueplan/physics/shot.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan::planner::detail {

inline constexpr double kGeneratedSpeedMin = 0.3;  // m/s
inline constexpr double kGeneratedSpeedMax = 3.0;  // m/s
inline constexpr int kGeneratedMaxCushions = 3;
inline constexpr double kGeneratedMargin = 0.1;    // m, balls kept this far inside the cushion noses

// Uniform doubles from a 64-bit Mersenne twister (53 random bits each).
class UniformStream {
 public:
  explicit UniformStream(uint64_t seed) : rng_(seed) {}
  double operator()(double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng_() >> 11) * 0x1.0p-53);
  }

 private:
  std::mt19937_64 rng_;
};

// A snooker table with its pockets, the default limits and tolerance, no positions yet.
problems::Problem generated_base();

// Speed uniform in [kGeneratedSpeedMin, kGeneratedSpeedMax], any aim, spin uniform over
// the disc of radius spin_max.
physics::Shot random_stroke(UniformStream& uniform, double spin_max);

// True when `result` came to rest on the table after at most kGeneratedMaxCushions
// cushions; then its rest position becomes the target and its cushion count the limits.
bool take_landing_as_target(const physics::ShotResult& result, problems::Problem* problem);

}  // namespace cueplan::planner::detail
