// Time per simulated shot, from the cue strike to rest, for one-, two- and
// three-cushion shots with and without obstacles, with the impact table, with the
// exact impact method and with the extrapolation method (the exact method before the
// Taylor method), all at the simulator's default accuracy where exact; and with 0, 1,
// 2, 8 and 15 object balls, the first struck full by a stun so that it takes the cue
// ball's route (BM_ShotBalls).
//
// Each benchmark cycles through 256 shots near a base shot (seeded jitter of aim,
// speed and spin), so a run does not time one lucky path. The scene is compiled (checked)
// once, as the planner does; BM_ShotCheckingTheScene times the one-off form that checks
// the scene on every call.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "cueplan/physics/impact_table.hpp"
#include "cueplan/physics/shot.hpp"
#include "cueplan/api/table_cache.hpp"

namespace {

using namespace cueplan::physics;

struct Case {
  const char* name;
  Shot base;
  int cushions;  // the route the base shot takes
};

// Base shots from (0.8, 0.5) on a snooker table without pockets.
const Case kCases[] = {
    {"one_cushion", {0.70, 60.0, 0.5, 0.0}, 1},
    {"two_cushions", {0.90, 30.0, 1.0, 0.5}, 2},
    {"three_cushions", {1.72, 15.0, 1.0, 1.0}, 3},
};

Scene scene(bool with_obstacles) {
  Scene s;  // no pockets: every shot comes to rest
  if (with_obstacles) s.obstacles = {{2.8, 0.35}, {0.6, 1.4}, {3.2, 1.55}, {1.9, 1.0}};
  return s;
}

const ImpactTable& table() {
  static const ImpactTable t = cueplan::cli::load_or_build_table(
      CushionParams{}, ImpactTableOptions{}, cueplan::cli::default_table_cache_dir());
  return t;
}

std::vector<Shot> jittered(const Shot& base) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Shot> shots;
  for (int i = 0; i < 256; ++i)
    shots.push_back({base.speed * (1 + 0.01 * u(rng)), base.aim_deg + 0.2 * u(rng),
                     base.topspin_k + 0.02 * u(rng), base.sidespin_k + 0.02 * u(rng)});
  return shots;
}

// Times simulate() over `shots` in turn from (0.8, 0.5); `scene` is a Scene or a
// CompiledScene.
template <class SceneForm>
void time_shots(benchmark::State& state, const SceneForm& scene, const std::vector<Shot>& shots,
                const SimulationOptions& o) {
  size_t i = 0;
  for (auto _ : state) {
    const ShotResult r = simulate(scene, {0.8, 0.5}, shots[i], o);
    benchmark::DoNotOptimize(r.final_position);
    if (++i == shots.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_Shot(benchmark::State& state, int which, bool obstacles, ImpactMethod method) {
  const Case& c = kCases[which];
  const CompiledScene s(scene(obstacles));
  SimulationOptions o;
  o.record_path = false;
  o.impact_method = method;
  if (method == ImpactMethod::table) {
    o.table = &table();
    o.impact_accuracy = 1e-5;  // the table's measured accuracy class
  }
  const std::vector<Shot> shots = jittered(c.base);
  double cushions = 0.0;
  for (const Shot& shot : shots) cushions += simulate(s, {0.8, 0.5}, shot, o).cushion_hits;
  time_shots(state, s, shots, o);
  // The route the case is named after, on average over its shots (obstacles may
  // stop some early).
  state.counters["mean_cushions"] = cushions / static_cast<double>(shots.size());
}

// The same shots through simulate(const Scene&), which checks the scene on every call.
void BM_ShotCheckingTheScene(benchmark::State& state, int which, bool obstacles) {
  SimulationOptions o;
  o.record_path = false;
  time_shots(state, scene(obstacles), jittered(kCases[which].base), o);
}

// ---- Object balls -------------------------------------------------------------
//
// A stroke along `aim` from (0.6, 0.6) that arrives stunned (no spin) 0.5 m on, in closed
// form as in the simulator's tests: with draw k_T < 0 the ball slides with w_y rising at
// 5 mu_s g / (2R) until it is zero at t_c, when it has gone V t_c - mu_s g t_c^2 / 2.
Shot stun_at(double arrival, double aim_deg, const Scene& s) {
  const double a = s.cloth.mu_slide * s.cloth.gravity, travel = 0.5;
  const double t = (-arrival + std::sqrt(arrival * arrival + 2.0 * a * travel)) / a;
  const double v = arrival + a * t;
  return {v, aim_deg, -2.5 * a * t / v, 0.0};
}

constexpr Vec2 kBallsCue{0.6, 0.6};

// Stun shots whose object ball, struck full 0.5 m on, takes the route the cue ball alone
// would take with the same stroke (one, two, three cushions), for the A/B of a shot with
// and without a ball to strike.
struct BallCase {
  const char* name;
  double arrival;  // m/s at the contact
  double aim_deg;
};
const BallCase kBallCases[] = {
    {"one_cushion", 1.0, 45.0}, {"two_cushions", 1.8, 28.0}, {"three_cushions", 2.6, 35.0}};

// The scene of a ball case: the struck ball on the line, and `extra` more balls seeded
// elsewhere on an open table (clear of the line's first metre and of one another).
Scene ball_scene(const BallCase& c, int balls) {
  Scene s;
  const double u = c.aim_deg * std::numbers::pi / 180.0;
  const double d = 0.5 + 2.0 * s.radius();
  if (balls > 0)
    s.balls.push_back({"red", {kBallsCue.x + d * std::cos(u), kBallsCue.y + d * std::sin(u)}});
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> x(0.1, s.length - 0.1), y(0.1, s.width - 0.1);
  while (static_cast<int>(s.balls.size()) < balls) {
    const Vec2 p{x(rng), y(rng)};
    bool clear = std::hypot(p.x - kBallsCue.x, p.y - kBallsCue.y) > 1.0;
    for (const ObjectBall& b : s.balls)
      clear = clear && std::hypot(p.x - b.position.x, p.y - b.position.y) > 3.0 * s.radius();
    if (clear) s.balls.push_back({"ball" + std::to_string(s.balls.size()), p});
  }
  return s;
}

// Times the stunned strokes of a ball case on a table with `balls` object balls (0: the
// cue ball alone, on the struck ball's route).
// How the impacts are resolved: exact at the default accuracy (1e-9; collisions at
// tolerance 1e-11), exact at 1e-7 (collisions at 1e-9, the collision library's sweet
// spot), or the impact table at its accuracy class (1e-5; collisions at 1e-7).
enum class Resolution { exact, exact_loose, table };
const char* to_string(Resolution r) {
  return r == Resolution::exact ? "exact" : r == Resolution::exact_loose ? "exact_1e-7" : "table";
}

void BM_ShotBalls(benchmark::State& state, int which, int balls, Resolution how) {
  const BallCase& c = kBallCases[which];
  const CompiledScene s(ball_scene(c, balls));
  if (!s.ok()) {
    state.SkipWithError(s.error()->message().c_str());
    return;
  }
  SimulationOptions o;
  o.record_path = false;
  if (how == Resolution::exact_loose) o.impact_accuracy = 1e-7;
  if (how == Resolution::table) {
    o.impact_method = ImpactMethod::table;
    o.table = &table();
    o.impact_accuracy = 1e-5;
  }
  // Alone, the cue ball arrives as fast as the struck ball leaves a full stun hit,
  // (1 + e_b) / 2 of the arrival speed, so that it takes the same route.
  const double restitution = s.scene().ball_contact.restitution;
  const double arrival = balls > 0 ? c.arrival : 0.5 * (1.0 + restitution) * c.arrival;
  const std::vector<Shot> shots = jittered(stun_at(arrival, c.aim_deg, s.scene()));
  double cushions = 0.0, contacts = 0.0, events = 0.0;
  for (const Shot& shot : shots) {
    const ShotResult r = simulate(s, kBallsCue, shot, o);
    for (const BallOutcome& b : r.balls) {
      cushions += b.cushion_hits;
      events += static_cast<double>(b.events.size());
      for (const ShotEvent& e : b.events) contacts += e.type == EventType::ball_contact ? 0.5 : 0.0;
    }
  }
  size_t i = 0;
  for (auto _ : state) {
    const ShotResult r = simulate(s, kBallsCue, shots[i], o);
    benchmark::DoNotOptimize(r.final_position);
    if (++i == shots.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
  const double n = static_cast<double>(shots.size());
  state.counters["mean_cushions"] = cushions / n;  // of every ball
  state.counters["mean_contacts"] = contacts / n;
  state.counters["mean_events"] = events / n;
}

// The same shots on a table with pockets: the standard capture circles against the
// snooker preset's jawed pockets (points and facings resolved by the cushion model,
// cushion noses cut at the points), plus a stroke rolled into the bottom-left corner.
// The jaws' cost is the ratio of the two (aim: at most 1.5).
const Case kPocketCases[] = {
    {"one_cushion", {0.70, 60.0, 0.5, 0.0}, 1},
    {"three_cushions", {1.72, 15.0, 1.0, 1.0}, 3},
    {"into_corner", {1.0, 180.0 + 32.0, 1.0, 0.0}, 0},
};

void BM_ShotPockets(benchmark::State& state, int which, bool jaws) {
  Scene table;
  if (jaws) {
    const PocketPreset p = *pocket_preset("snooker");
    table.pockets = jawed_pockets(table.length, table.width, p.corner, p.middle);
  } else {
    table.pockets = standard_pockets(table.length, table.width, kDefaultPocketRadius);
  }
  const CompiledScene s(table);
  SimulationOptions o;
  o.record_path = false;
  const std::vector<Shot> shots = jittered(kPocketCases[which].base);
  double pocketed = 0.0, jaw_hits = 0.0, events = 0.0;
  for (const Shot& shot : shots) {
    const ShotResult r = simulate(s, {0.8, 0.5}, shot, o);
    pocketed += r.status == ShotStatus::pocketed ? 1.0 : 0.0;
    jaw_hits += r.balls[0].jaw_hits;
    events += static_cast<double>(r.events.size());
  }
  time_shots(state, s, shots, o);
  const double n = static_cast<double>(shots.size());
  state.counters["pocketed"] = pocketed / n;
  state.counters["mean_jaw_hits"] = jaw_hits / n;
  state.counters["mean_events"] = events / n;
}

void register_all() {
  for (int which = 0; which < 3; ++which)
    for (bool jaws : {false, true}) {
      const std::string name = std::string("BM_ShotPockets/") + kPocketCases[which].name +
                               (jaws ? "/jaws" : "/capture_circles");
      benchmark::RegisterBenchmark(name.c_str(), BM_ShotPockets, which, jaws);
    }
  for (int which = 0; which < 3; ++which)
    for (Resolution how : {Resolution::exact, Resolution::exact_loose, Resolution::table})
      for (int balls : {0, 1, 2, 8, 15}) {
        const std::string name = std::string("BM_ShotBalls/") + kBallCases[which].name + "/" +
                                 std::to_string(balls) + "_balls/" + to_string(how);
        benchmark::RegisterBenchmark(name.c_str(), BM_ShotBalls, which, balls, how);
      }
  for (int which = 0; which < 3; ++which)
    for (bool obstacles : {false, true})
      for (ImpactMethod method :
           {ImpactMethod::table, ImpactMethod::exact, ImpactMethod::extrapolation}) {
        std::string name = std::string("BM_Shot/") + kCases[which].name +
                           (obstacles ? "/obstacles/" : "/open/") + to_string(method);
        benchmark::RegisterBenchmark(name.c_str(), BM_Shot, which, obstacles, method);
      }
  for (bool obstacles : {false, true}) {
    const std::string name = std::string("BM_ShotCheckingTheScene/one_cushion") +
                             (obstacles ? "/obstacles" : "/open") + "/exact";
    benchmark::RegisterBenchmark(name.c_str(), BM_ShotCheckingTheScene, 0, obstacles);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
