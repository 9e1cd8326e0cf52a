// Time per ball-ball collision for each model and method, with each configuration's error
// against a converged reference on the same inputs, so run time and error come from one
// run.
//
//   bench_collision --benchmark_format=json > collision.json
//
// Inputs: 4096 cue shots drawn uniformly (seeded): the cue ball at V in (0.01, 5) m/s
// with k_T, k_S in [-3, 3] cutting an object ball at rest by c in (-89, 89) deg; and
// 4096 rolling cue balls (k_T = 1, k_S in [-1, 1]), the commonest shot; and 4096 stun
// shots nearly full ball (V in (0.3, 3) m/s, |c| < 2 deg, residual spins up to 0.02 V / R
// about every axis), the hard case of the extrapolation method. The reference is
// mathavan_2014 resolved by the extrapolation method at tolerance 1e-14 (it agrees with
// the Taylor method at 1e-14 to about 1e-12). For the closed form the "error" is the
// difference between the two models, not a numerical error.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "cueplan/physics/ball_collision.hpp"

namespace {

using namespace cueplan::physics;

struct Sample {
  double speed;
  CutShot shot;
  CollisionResult reference;
};

CollisionResult collide(const BallBallParams& p, const CutShot& s, const CollisionOptions& o) {
  return resolve_table_collision(p, s.cue_centre, s.cue_ball, s.object_centre, s.object_ball, o);
}

enum class Kind { uniform, rolling, stun };

std::vector<Sample> make_samples(Kind kind) {
  const BallBallParams params;
  std::mt19937_64 rng(kind == Kind::rolling ? 2014 : (kind == Kind::stun ? 2026 : 1406));
  std::uniform_real_distribution<double> v(0.01, 5.0), cut(-89.0, 89.0), k(-3.0, 3.0),
      side(-1.0, 1.0), stun_v(0.3, 3.0), stun_cut(-2.0, 2.0), residual(-0.02, 0.02);
  CollisionOptions converged;
  converged.method = CollisionMethod::extrapolation;
  converged.tolerance = 1e-14;
  converged.max_steps = 1000000;
  std::vector<Sample> out;
  for (int i = 0; i < 4096; ++i) {
    Sample s;
    if (kind == Kind::stun) {
      s.speed = stun_v(rng);
      const double c = stun_cut(rng), unit = s.speed / params.radius;
      const double x = residual(rng), y = residual(rng), z = residual(rng);
      s.shot = cut_shot(s.speed, c, {x * unit, y * unit, z * unit}, params.radius);
    } else {
      const bool rolling = kind == Kind::rolling;
      s.speed = v(rng);
      const double c = cut(rng);
      const double topspin_k = rolling ? 1.0 : k(rng), sidespin_k = rolling ? side(rng) : k(rng);
      const double unit = s.speed / params.radius;
      s.shot = cut_shot(s.speed, c, {0.0, topspin_k * unit, sidespin_k * unit}, params.radius);
    }
    s.reference = collide(params, s.shot, converged);
    out.push_back(s);
  }
  return out;
}

const std::vector<Sample>& samples() {
  static const std::vector<Sample> all = make_samples(Kind::uniform);
  return all;
}

const std::vector<Sample>& rolling_samples() {
  static const std::vector<Sample> all = make_samples(Kind::rolling);
  return all;
}

const std::vector<Sample>& stun_samples() {
  static const std::vector<Sample> all = make_samples(Kind::stun);
  return all;
}

// Error of one result against the reference: both balls' outgoing velocity and R * spin
// over V.
double state_error(const BallBallParams& p, const CollisionResult& r, const Sample& s) {
  double m = 0.0;
  for (const auto& [a, b] :
       {std::pair{r.ball_i, s.reference.ball_i}, std::pair{r.ball_j, s.reference.ball_j}}) {
    const Vec3 dv = a.velocity - b.velocity, dw = a.spin - b.spin;
    m = std::max({m, std::abs(dv.x), std::abs(dv.y), p.radius * std::abs(dw.x),
                  p.radius * std::abs(dw.y), p.radius * std::abs(dw.z)});
  }
  return m / s.speed;
}

double direction_deg(Vec3 v) { return std::atan2(v.y, v.x) * 180.0 / std::numbers::pi; }

void run_collisions(benchmark::State& state, const BallBallParams& params,
                    const CollisionOptions& options, const std::vector<Sample>& in = samples()) {
  // Accuracy over every sample, outside the timed loop.
  std::vector<double> errors;
  double worst_angle = 0.0;
  long long evaluations = 0;
  int worst_rhs = 0;
  for (const Sample& s : in) {
    const CollisionResult r = collide(params, s.shot, options);
    errors.push_back(state_error(params, r, s));
    worst_angle = std::max(worst_angle, std::abs(direction_deg(r.ball_j.velocity) -
                                                 direction_deg(s.reference.ball_j.velocity)));
    evaluations += r.rhs_evaluations;
    worst_rhs = std::max(worst_rhs, r.rhs_evaluations);
  }
  std::sort(errors.begin(), errors.end());

  size_t i = 0;
  for (auto _ : state) {
    const CollisionResult r = collide(params, in[i].shot, options);
    benchmark::DoNotOptimize(r.ball_j.velocity.x);
    if (++i == in.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["max_state_err"] = errors.back();
  state.counters["median_state_err"] = errors[errors.size() / 2];
  state.counters["max_object_angle_err_deg"] = worst_angle;
  state.counters["rhs_per_collision"] =
      static_cast<double>(evaluations) / static_cast<double>(in.size());
  state.counters["max_rhs"] = worst_rhs;
}

void BM_CollisionExact(benchmark::State& state) {
  CollisionOptions o;
  o.tolerance = std::pow(10.0, -static_cast<double>(state.range(0)));
  run_collisions(state, BallBallParams{}, o);
}
BENCHMARK(BM_CollisionExact)->ArgName("tol_exp")->Arg(6)->Arg(9)->Arg(10)->Arg(11)->Arg(12)->Arg(13);

void BM_CollisionExtrapolation(benchmark::State& state) {
  CollisionOptions o;
  o.method = CollisionMethod::extrapolation;
  o.tolerance = std::pow(10.0, -static_cast<double>(state.range(0)));
  run_collisions(state, BallBallParams{}, o);
}
BENCHMARK(BM_CollisionExtrapolation)
    ->ArgName("tol_exp")->Arg(6)->Arg(9)->Arg(10)->Arg(11)->Arg(12)->Arg(13);

void BM_CollisionPaper(benchmark::State& state) {
  CollisionOptions o;
  o.method = CollisionMethod::paper;
  o.paper_steps = static_cast<int>(state.range(0));
  run_collisions(state, BallBallParams{}, o);
}
BENCHMARK(BM_CollisionPaper)->ArgName("N")->Arg(500)->Arg(5000)->Arg(50000);

void BM_CollisionClosedForm(benchmark::State& state) {
  BallBallParams p;
  p.model = BallModel::frictional_inelastic;
  p.friction = state.range(0) == 0 ? BallFriction::constant : BallFriction::speed_dependent;
  run_collisions(state, p, CollisionOptions{});
}
BENCHMARK(BM_CollisionClosedForm)->ArgName("speed_dependent")->Arg(0)->Arg(1);

// Natural roll: the commonest cue ball at an object ball.
void BM_CollisionRollingExact(benchmark::State& state) {
  CollisionOptions o;
  o.tolerance = std::pow(10.0, -static_cast<double>(state.range(0)));
  run_collisions(state, BallBallParams{}, o, rolling_samples());
}
BENCHMARK(BM_CollisionRollingExact)->ArgName("tol_exp")->Arg(9)->Arg(12);

void BM_CollisionRollingExtrapolation(benchmark::State& state) {
  CollisionOptions o;
  o.method = CollisionMethod::extrapolation;
  o.tolerance = std::pow(10.0, -static_cast<double>(state.range(0)));
  run_collisions(state, BallBallParams{}, o, rolling_samples());
}
BENCHMARK(BM_CollisionRollingExtrapolation)->ArgName("tol_exp")->Arg(9)->Arg(12);

// Stun nearly full ball: the slip between the balls is small and turns as it shrinks.
void BM_CollisionStun(benchmark::State& state) {
  CollisionOptions o;
  o.method = state.range(0) == 0 ? CollisionMethod::exact : CollisionMethod::extrapolation;
  o.tolerance = std::pow(10.0, -static_cast<double>(state.range(1)));
  run_collisions(state, BallBallParams{}, o, stun_samples());
}
BENCHMARK(BM_CollisionStun)
    ->ArgNames({"extrapolation", "tol_exp"})
    ->Args({0, 9})->Args({1, 9})->Args({0, 11})->Args({1, 11})->Args({0, 12})->Args({1, 12});

}  // namespace

BENCHMARK_MAIN();
