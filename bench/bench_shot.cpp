// Time per simulated shot, from the cue strike to rest, for one-, two- and
// three-cushion shots with and without obstacles, with the impact table, with the
// exact impact method and with the extrapolation method (the exact method before the
// Taylor method), all at the simulator's default accuracy where exact.
//
// Each benchmark cycles through 256 shots near a base shot (seeded jitter of aim,
// speed and spin), so a run does not time one lucky path. The scene is compiled (checked)
// once, as the planner does; BM_ShotCheckingTheScene times the one-off form that checks
// the scene on every call.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "cueplan/physics/impact_table.hpp"
#include "cueplan/physics/shot.hpp"
#include "table_cache.hpp"

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

void register_all() {
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
