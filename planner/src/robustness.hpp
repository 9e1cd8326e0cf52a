// A player's execution noise: seeded draws, noisy strokes, and how often they land.
#pragma once

#include <cstdint>
#include <vector>

#include "cueplan/planner/planner.hpp"
#include "task.hpp"

namespace cueplan::planner::detail {

// Independent seeds for independent streams (splitmix64 of seed and stream).
uint64_t stream_seed(uint64_t seed, uint64_t stream);

// One stroke's errors in standard deviations: aim, speed, tip offset right and up.
struct NoiseDraw {
  double aim = 0.0, speed = 0.0, right = 0.0, up = 0.0;
};
// `samples` draws from a seeded stream; the same seed gives the same draws on every
// platform (the normals come from mt19937_64 by Box-Muller, not from <random>'s
// implementation-defined distributions).
std::vector<NoiseDraw> noise_draws(int samples, uint64_t seed);

// The stroke a player makes aiming at `shot` with errors `draw` scaled by `noise`.
// False for a miscue (tip offset beyond miscue_k) or a stroke without speed.
bool noisy_stroke(const physics::Shot& shot, const NoiseDraw& draw, const NoiseModel& noise,
                  double radius, double miscue_k, physics::Shot* out);

// The spin beyond which a noisy stroke miscues: the larger of 1.25 (d = R/2) and the
// problem's own spin limit.
double miscue_limit(const problems::Problem& problem);

// Mean over `draws` of a soft landing score, 1 / (1 + (miss / tolerance)^2), and 0
// for a stroke that fails (miscue, pocketed, obstacle, cushions outside the limits).
// The robust objective, with common random numbers: unlike the 0/1 landing count it
// is smooth in the stroke and keeps telling near misses from wide ones when only a
// few of the draws land, and it rises as the landings gather round the target.
// *simulations counts the strokes simulated.
double soft_success(const Task& task, const physics::Shot& shot,
                    const std::vector<NoiseDraw>& draws, const NoiseModel& noise,
                    const physics::SimulationOptions& simulation, int* simulations);

// planner::success_probability on a checked task.
double success_probability(const Task& task, const physics::Shot& shot, const NoiseModel& noise,
                           int samples, uint64_t seed, const physics::SimulationOptions& simulation);

}  // namespace cueplan::planner::detail
