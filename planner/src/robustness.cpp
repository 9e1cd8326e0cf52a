// Execution noise and success probabilities.
#include "robustness.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace cueplan::planner {
namespace detail {
namespace {

// Uniform in (0, 1) from the top 53 bits.
double open_uniform(std::mt19937_64& rng) {
  return (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53;
}

}  // namespace

uint64_t stream_seed(uint64_t seed, uint64_t stream) {
  uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (stream + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::vector<NoiseDraw> noise_draws(int samples, uint64_t seed) {
  std::mt19937_64 rng(stream_seed(seed, 0x6e6f697365ULL));  // "noise"
  std::vector<NoiseDraw> draws(static_cast<size_t>(std::max(samples, 0)));
  // Box-Muller: two uniforms give two independent standard normals.
  auto pair = [&](double* a, double* b) {
    const double r = std::sqrt(-2.0 * std::log(open_uniform(rng)));
    const double t = 2.0 * std::numbers::pi * open_uniform(rng);
    *a = r * std::cos(t);
    *b = r * std::sin(t);
  };
  for (NoiseDraw& d : draws) {
    pair(&d.aim, &d.speed);
    pair(&d.right, &d.up);
  }
  return draws;
}

bool noisy_stroke(const physics::Shot& shot, const NoiseDraw& draw, const NoiseModel& noise,
                  double radius, double miscue_k, physics::Shot* out) {
  const double s = noise.scale;
  // Tip offsets d become spin by k = 2.5 d / R (PHYSICS.md, "Cue strike").
  const double dk = physics::kSpinPerTipOffset * noise.tip_offset * s / radius;
  out->speed = shot.speed + noise.speed * s * draw.speed;
  out->aim_deg = shot.aim_deg + noise.aim_deg * s * draw.aim;
  out->sidespin_k = shot.sidespin_k + dk * draw.right;
  out->topspin_k = shot.topspin_k + dk * draw.up;
  if (!(out->speed > 0.0)) return false;
  return std::hypot(out->topspin_k, out->sidespin_k) <= miscue_k * (1.0 + 1e-12);
}

double miscue_limit(const problems::Problem& problem) {
  return std::max(physics::kMiscueSpin, problem.limits.spin_max);
}

double soft_success(const Task& task, const physics::Shot& shot,
                    const std::vector<NoiseDraw>& draws, const NoiseModel& noise,
                    const physics::SimulationOptions& simulation, int* simulations) {
  if (draws.empty()) return 0.0;
  const problems::Problem& problem = task.problem;
  const double radius = problem.scene.radius();
  const double miscue = miscue_limit(problem);
  const problems::Limits& l = problem.limits;
  double sum = 0.0;
  for (const NoiseDraw& d : draws) {
    physics::Shot s;
    if (!noisy_stroke(shot, d, noise, radius, miscue, &s)) continue;
    const physics::ShotResult r = task.simulate(s, simulation);
    ++*simulations;
    if (r.status != physics::ShotStatus::rest || r.cushion_hits < l.cushions_min ||
        r.cushion_hits > l.cushions_max)
      continue;
    // A Cauchy kernel: 1 on the target, 1/2 at the tolerance, and still telling near
    // misses from wide ones a few tolerances out, where most noisy strokes land.
    const double x = problems::miss_distance(problem, r) / problem.tolerance;
    sum += 1.0 / (1.0 + x * x);
  }
  return sum / static_cast<double>(draws.size());
}

}  // namespace detail

double success_probability(const problems::Problem& problem, const physics::Shot& shot,
                           const NoiseModel& noise, int samples, uint64_t seed,
                           const physics::SimulationOptions& simulation) {
  return detail::success_probability(detail::Task(problem), shot, noise, samples, seed, simulation);
}

namespace detail {

double success_probability(const Task& task, const physics::Shot& shot, const NoiseModel& noise,
                           int samples, uint64_t seed, const physics::SimulationOptions& simulation) {
  if (samples <= 0 || noise.validate()) return 0.0;
  const problems::Problem& problem = task.problem;
  physics::SimulationOptions quiet = simulation;
  quiet.record_path = false;
  const double radius = problem.scene.radius();
  const double miscue = miscue_limit(problem);
  int landed = 0;
  for (const NoiseDraw& d : noise_draws(samples, seed)) {
    physics::Shot s;
    if (!noisy_stroke(shot, d, noise, radius, miscue, &s)) continue;
    if (problems::reaches_target(problem, task.simulate(s, quiet))) ++landed;
  }
  return static_cast<double>(landed) / samples;
}

}  // namespace detail

}  // namespace cueplan::planner
