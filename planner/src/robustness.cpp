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

NoiseStream::NoiseStream(uint64_t seed) : rng_(stream_seed(seed, 0x6e6f697365ULL)) {}  // "noise"

void NoiseStream::grow_to(size_t count, Clock::time_point deadline) {
  constexpr size_t kChunk = 4096;  // draws between looks at the clock
  const bool timed = deadline != Clock::time_point::max();
  // Box-Muller: two uniforms give two independent standard normals.
  auto pair = [&](double* a, double* b) {
    const double r = std::sqrt(-2.0 * std::log(open_uniform(rng_)));
    const double t = 2.0 * std::numbers::pi * open_uniform(rng_);
    *a = r * std::cos(t);
    *b = r * std::sin(t);
  };
  while (draws_.size() < count) {
    if (timed && Clock::now() >= deadline) return;
    const size_t end = std::min(count, draws_.size() + kChunk);
    while (draws_.size() < end) {
      NoiseDraw d;
      pair(&d.aim, &d.speed);
      pair(&d.right, &d.up);
      draws_.push_back(d);
    }
  }
}

std::vector<NoiseDraw> noise_draws(int samples, uint64_t seed) {
  NoiseStream stream(seed);
  stream.grow_to(static_cast<size_t>(std::max(samples, 0)));
  return stream.draws();
}

bool noisy_stroke(const physics::Shot& shot, const NoiseDraw& draw, const NoiseModel& noise,
                  double radius, double miscue_k, double squirt_deg, physics::Shot* out) {
  const double s = noise.scale;
  // Tip offsets d become spin by k = 2.5 d / R (PHYSICS.md, "Cue strike"): a fixed
  // deviation, and one that grows with the offset intended each way.
  const double dk = physics::kSpinPerTipOffset * noise.tip_offset * s / radius;
  const double rel = noise.tip_offset_relative * s;
  const double dk_right = dk + rel * std::abs(shot.sidespin_k);
  const double dk_up = dk + rel * std::abs(shot.topspin_k);
  // The aim's deviation and the misjudged squirt, independent normals, add in quadrature.
  const double aim_sd = std::hypot(noise.aim_deg, noise.squirt_judgement * squirt_deg) * s;
  *out = shot;
  out->speed = shot.speed + noise.speed * s * draw.speed;
  out->aim_deg = shot.aim_deg + aim_sd * draw.aim;
  if (noise.bridge_length > 0.0) {
    // The cue pivots at the bridge: the tip d (m) to the right turns it clockwise.
    const double d_right = dk_right * draw.right * radius / physics::kSpinPerTipOffset;
    out->aim_deg -= d_right / noise.bridge_length * (180.0 / std::numbers::pi);
  }
  out->sidespin_k = shot.sidespin_k + dk_right * draw.right;
  out->topspin_k = shot.topspin_k + dk_up * draw.up;
  if (!(out->speed > 0.0)) return false;
  return std::hypot(out->topspin_k, out->sidespin_k) <= miscue_k * (1.0 + 1e-12);
}

double intended_squirt_deg(const problems::Problem& problem, const physics::Shot& shot) {
  const physics::Scene& scene = problem.scene;
  return physics::squirt_angle_deg(scene.cue, scene.ball_and_cushion.mass, scene.radius(),
                                   shot.sidespin_k);
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
  const double squirt = intended_squirt_deg(problem, shot);
  double sum = 0.0;
  for (const NoiseDraw& d : draws) {
    physics::Shot s;
    if (!noisy_stroke(shot, d, noise, radius, miscue, squirt, &s)) continue;
    const physics::ShotResult r = task.simulate(s, simulation);
    ++*simulations;
    // At rest after allowed cushions (and, with a pot, the pot made cleanly).
    if (!problems::pot_made(problems::outcome_failure(problem, r))) continue;
    // A Cauchy kernel: 1 on the target, 1/2 at the tolerance, and still telling near
    // misses from wide ones a few tolerances out, where most noisy strokes land.
    const double x = problems::miss_distance(problem, r) / problem.tolerance;
    // Position play: weighed by the landing's value for the next pot.
    const double next = task.next_field ? task.next_field->value(r.final_position) : 1.0;
    sum += next / (1.0 + x * x);
  }
  return sum / static_cast<double>(draws.size());
}

}  // namespace detail

Success estimate_success(const problems::Problem& problem, const physics::Shot& shot,
                         const NoiseModel& noise, int samples, uint64_t seed,
                         const physics::SimulationOptions& simulation) {
  if (samples <= 0 || noise.validate()) return {};
  detail::Task task(problem);
  if (!problem.next.empty())
    task.next_field = std::make_shared<const PositionField>(PositionField::for_problem(problem, noise));
  return detail::sample_success(task, shot, detail::noise_draws(samples, seed), noise, simulation)
      .success;
}

std::vector<NoisyLanding> noisy_landings(const problems::Problem& problem, const physics::Shot& shot,
                                         const NoiseModel& noise, int samples, uint64_t seed,
                                         const physics::SimulationOptions& simulation) {
  std::vector<NoisyLanding> out;
  if (samples <= 0 || noise.validate()) return out;
  const detail::Task task(problem);
  physics::SimulationOptions quiet = simulation;
  quiet.record_path = false;
  const double radius = problem.scene.radius();
  const double miscue = detail::miscue_limit(problem);
  const double squirt = detail::intended_squirt_deg(problem, shot);
  for (const detail::NoiseDraw& d : detail::noise_draws(samples, seed)) {
    physics::Shot s;
    if (!detail::noisy_stroke(shot, d, noise, radius, miscue, squirt, &s)) continue;
    const physics::ShotResult r = task.simulate(s, quiet);
    if (r.status != physics::ShotStatus::rest) continue;
    out.push_back({r.final_position, problems::pot_made(problems::outcome_failure(problem, r))});
  }
  return out;
}

double success_probability(const problems::Problem& problem, const physics::Shot& shot,
                           const NoiseModel& noise, int samples, uint64_t seed,
                           const physics::SimulationOptions& simulation) {
  return estimate_success(problem, shot, noise, samples, seed, simulation).both.p;
}

Estimate wilson_estimate(int successes, int samples) {
  Estimate e;
  e.samples = std::max(samples, 0);
  e.successes = std::clamp(successes, 0, e.samples);
  if (e.samples == 0) return e;
  // Wilson score interval: the p whose normal test at z does not reject the count.
  constexpr double z = 1.959963984540054;  // two-sided 95 %
  const double n = e.samples;
  const double p = e.successes / n;
  const double z2n = z * z / n;
  const double centre = (p + z2n / 2.0) / (1.0 + z2n);
  const double half = z / (1.0 + z2n) * std::sqrt(p * (1.0 - p) / n + z2n / (4.0 * n));
  e.p = p;
  e.low = e.successes == 0 ? 0.0 : std::max(0.0, centre - half);
  e.high = e.successes == e.samples ? 1.0 : std::min(1.0, centre + half);
  return e;
}

namespace detail {

double next_uniform(size_t draw) {
  return static_cast<double>(stream_seed(0x6e657874ULL, draw) >> 11) * 0x1.0p-53;  // "next"
}

uint8_t judge(const Task& task, const physics::ShotResult& result, size_t draw, float* next_p) {
  const problems::Failure failure = problems::outcome_failure(task.problem, result);
  const bool pot_made = problems::pot_made(failure), solves = failure == problems::Failure::none;
  if (next_p) *next_p = 0.0f;
  if (task.next_field && pot_made) {
    // Position play: the next pot from where the cue ball stops, drawn by this draw's
    // uniform (the same for every stroke: paired comparisons stay paired).
    uint8_t bits = kPotted;
    if (solves) {
      bits |= kOnTarget;
      const PositionField& field = *task.next_field;
      if (next_p) *next_p = static_cast<float>(field.next_shot(result.final_position).p);
      if (next_uniform(draw) < field.value(result.final_position)) bits |= kPositioned;
    }
    return bits;
  }
  if (solves) return kSucceeded;
  // Without a pot there is nothing to pot: every stroke played counts as potting.
  return !task.problem.pot || pot_made ? kPotted : 0;
}

Success success_of(const Task& task, const std::vector<uint8_t>& outcomes,
                   const std::vector<float>& next_p) {
  int potted = 0, both = 0;
  for (uint8_t o : outcomes) {
    potted += (o & kPotted) != 0;
    both += (o & kSucceeded) == kSucceeded;
  }
  const int n = static_cast<int>(outcomes.size());
  Success s;
  s.both = wilson_estimate(both, n);
  if (!task.problem.pot) {
    s.position = s.both;
    return s;
  }
  // P(pot) over every stroke; P(position | pot) over the strokes that potted.
  s.pot = wilson_estimate(potted, n);
  s.position = wilson_estimate(both, potted);
  if (task.next_field) {
    // Position: the target alone; next: the mean P(next pot) over the strokes that left
    // the cue ball on the target after the pot, its normal interval widened by the
    // closed form's allowance.
    int on_target = 0;
    double sum = 0.0, sum2 = 0.0;
    for (size_t i = 0; i < outcomes.size(); ++i) {
      if ((outcomes[i] & kOnTarget) == 0) continue;
      ++on_target;
      const double q = i < next_p.size() ? next_p[i] : 0.0;
      sum += q;
      sum2 += q * q;
    }
    s.position = wilson_estimate(on_target, potted);
    Estimate next;
    next.samples = on_target;
    next.successes = static_cast<int>(std::lround(sum));
    if (on_target > 0) {
      const double m = on_target;
      next.p = sum / m;
      const double var = std::max(0.0, sum2 / m - next.p * next.p);
      const double half = 1.959963984540054 * std::sqrt(var / m);
      // The band the next pot's chance lies in for the middle 80 % of the landings (where
      // the player will in fact be left), never narrower than the mean's 95 % interval,
      // widened by the closed form's allowance.
      std::vector<double> landed;
      for (size_t i = 0; i < outcomes.size(); ++i)
        if ((outcomes[i] & kOnTarget) != 0) landed.push_back(i < next_p.size() ? next_p[i] : 0.0);
      std::sort(landed.begin(), landed.end());
      const auto quantile = [&](double q) {
        return landed[static_cast<size_t>(std::lround(q * static_cast<double>(landed.size() - 1)))];
      };
      next.low = std::max(0.0, std::min(next.p - half, quantile(0.1)) - kFieldError);
      next.high = std::min(1.0, std::max(next.p + half, quantile(0.9)) + kFieldError);
    }
    s.next = next;
  }
  return s;
}

Sampled sample_success(const Task& task, const physics::Shot& shot,
                       std::span<const NoiseDraw> draws, const NoiseModel& noise,
                       const physics::SimulationOptions& simulation, Clock::time_point deadline) {
  Sampled out;
  extend_sample(task, shot, draws, noise, simulation, deadline, &out);
  return out;
}

void extend_sample(const Task& task, const physics::Shot& shot, std::span<const NoiseDraw> draws,
                   const NoiseModel& noise, const physics::SimulationOptions& simulation,
                   Clock::time_point deadline, Sampled* sampled) {
  const problems::Problem& problem = task.problem;
  physics::SimulationOptions quiet = simulation;
  quiet.record_path = false;
  const double radius = problem.scene.radius();
  const double miscue = miscue_limit(problem);
  const double squirt = intended_squirt_deg(problem, shot);
  const bool timed = deadline != Clock::time_point::max();
  std::vector<uint8_t>& outcomes = sampled->outcomes;
  outcomes.reserve(draws.size());
  std::vector<float>& next_p = sampled->next_p;
  next_p.resize(outcomes.size(), 0.0f);
  for (size_t i = outcomes.size(); i < draws.size(); ++i) {
    if (timed && Clock::now() >= deadline) break;
    physics::Shot s;
    if (!noisy_stroke(shot, draws[i], noise, radius, miscue, squirt, &s)) {
      outcomes.push_back(0);  // a miscue fails every condition
      next_p.push_back(0.0f);
      continue;
    }
    float q = 0.0f;
    outcomes.push_back(judge(task, task.simulate(s, quiet), i, &q));
    next_p.push_back(q);
    ++sampled->simulations;
  }
  sampled->success = success_of(task, outcomes, next_p);
}

}  // namespace detail

}  // namespace cueplan::planner
