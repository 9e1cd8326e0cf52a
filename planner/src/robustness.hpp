// A player's execution noise: seeded draws, noisy strokes, and how often they land.
#pragma once

#include <chrono>
#include <cstdint>
#include <random>
#include <span>
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

using Clock = std::chrono::steady_clock;

// The same stream drawn as far as it is needed: draws() are always the first draws of
// noise_draws(n, seed).
class NoiseStream {
 public:
  explicit NoiseStream(uint64_t seed);
  // Draws until there are `count`, or until `deadline` passes (checked every few
  // thousand draws).
  void grow_to(size_t count, Clock::time_point deadline = Clock::time_point::max());
  const std::vector<NoiseDraw>& draws() const { return draws_; }

 private:
  std::mt19937_64 rng_;
  std::vector<NoiseDraw> draws_;
};

// The stroke a player makes aiming at `shot` with errors `draw` scaled by `noise`:
// the aim errs by noise.aim_deg and, with side, by the misjudged squirt (squirt_deg, the
// intended stroke's, times noise.squirt_judgement; the two in quadrature, one draw); the
// tip offset each way by noise.tip_offset plus noise.tip_offset_relative of the offset
// intended that way, the sideways error turning the cue about the bridge
// (noise.bridge_length). False for a miscue (tip offset beyond miscue_k) or a stroke
// without speed.
bool noisy_stroke(const physics::Shot& shot, const NoiseDraw& draw, const NoiseModel& noise,
                  double radius, double miscue_k, double squirt_deg, physics::Shot* out);
// The squirt (deg) of `shot` on the problem's table, with its cue (physics::squirt_angle_deg).
double intended_squirt_deg(const problems::Problem& problem, const physics::Shot& shot);

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

// What one noisy stroke did, as bits: the pot's conditions held (always set without a
// pot, unless the stroke miscued), and the position's too.
inline constexpr uint8_t kPotted = 1;
inline constexpr uint8_t kPositioned = 2;
inline constexpr uint8_t kSucceeded = kPotted | kPositioned;
// Position play (task.next_field): kPositioned means the target held (or there is none)
// and the next pot, drawn as made with the landing's value, was made; kOnTarget the
// target alone.
inline constexpr uint8_t kOnTarget = 4;

// The outcome bits of a stroke's simulated result on the task's problem; `draw` is the
// index of the noise draw (position play draws the next pot by it: common numbers).
// *next_p, when given, is P(next pot) from the landing (0 unless pot and target held).
uint8_t judge(const Task& task, const physics::ShotResult& result, size_t draw = 0,
              float* next_p = nullptr);
// The uniform in [0, 1) a draw's next pot is decided by.
double next_uniform(size_t draw);

// A Monte Carlo estimate draw by draw: outcomes[i] is what the noisy stroke of draws[i]
// did, for the draws simulated before the deadline (a prefix of them), so two strokes
// sampled with the same draws can be compared pair by pair (common random numbers).
struct Sampled {
  std::vector<uint8_t> outcomes;
  std::vector<float> next_p;  // position play: P(next pot) from each draw's landing
  Success success;
  int simulations = 0;  // strokes simulated (a miscue is not simulated)
};

// `shot` played with each of `draws` until they run out or `deadline` passes.
Sampled sample_success(const Task& task, const physics::Shot& shot,
                       std::span<const NoiseDraw> draws, const NoiseModel& noise,
                       const physics::SimulationOptions& simulation,
                       Clock::time_point deadline = Clock::time_point::max());
// The same, continuing *sampled with the draws after those it has.
void extend_sample(const Task& task, const physics::Shot& shot, std::span<const NoiseDraw> draws,
                   const NoiseModel& noise, const physics::SimulationOptions& simulation,
                   Clock::time_point deadline, Sampled* sampled);

// The success of a set of outcome bits (all of them, in order).
// With position play, `next_p` (one per outcome) gives success.next.
Success success_of(const Task& task, const std::vector<uint8_t>& outcomes,
                   const std::vector<float>& next_p = {});

}  // namespace cueplan::planner::detail
