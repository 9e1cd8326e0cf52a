// "What spin lands here?": one speed and aim, every spin on a square grid over the
// tip-offset disc, each simulated to rest on the problem's scene.
#include "cueplan/planner/spin_map.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>
#include <vector>

namespace cueplan::planner {
namespace {

namespace phys = cueplan::physics;

std::string describe(const char* field, const char* rule, double value) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s %s, got %.10g", field, rule, value);
  return buf;
}

// k = (5/2) d / R for a centred-impulse cue (PHYSICS.md, "Cue strike").
constexpr double kSpinPerTipOffset = 2.5;

// The grid's spins inside the disc of radius spin_max, row by row from the top
// (most topspin) down, each row from the left (most left spin) to the right. The
// coordinate of index i is spin_max (2i - (n - 1)) / (n - 1), so an odd grid holds
// k = 0 exactly.
std::vector<SpinMapPoint> grid_points(int grid, double spin_max) {
  std::vector<SpinMapPoint> points;
  const double half = 0.5 * static_cast<double>(grid - 1);
  const auto coordinate = [&](int i) { return spin_max * (static_cast<double>(i) - half) / half; };
  // Points on the rim count as inside despite rounding.
  const double rim = spin_max * spin_max * (1.0 + 1e-12);
  for (int row = grid - 1; row >= 0; --row) {
    const double topspin = coordinate(row);
    for (int col = 0; col < grid; ++col) {
      const double sidespin = coordinate(col);
      if (topspin * topspin + sidespin * sidespin > rim) continue;
      SpinMapPoint p;
      p.topspin_k = topspin;
      p.sidespin_k = sidespin;
      p.tip_right = sidespin / kSpinPerTipOffset;
      p.tip_up = topspin / kSpinPerTipOffset;
      points.push_back(p);
    }
  }
  return points;
}

// Simulates one grid spin and records where it stops against the target.
void land(const problems::Problem& problem, double speed, double aim_deg,
          const phys::SimulationOptions& simulation, SpinMapPoint* p) {
  const phys::Shot shot{speed, aim_deg, p->topspin_k, p->sidespin_k};
  const phys::ShotResult r = phys::simulate(problem.scene, problem.cue_ball, shot, simulation);
  p->outcome = r.status;
  p->final_position = r.final_position;
  p->miss_distance = problems::miss_distance(problem, r);
  p->cushion_hits = r.cushion_hits;
  p->lands = problems::reaches_target(problem, r);
}

unsigned worker_count(int requested, size_t items) {
  const unsigned wanted = requested > 0 ? static_cast<unsigned>(requested)
                                        : std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(std::max<size_t>(1, std::min<size_t>(wanted, items)));
}

}  // namespace

std::string SpinMapOptions::validate() const {
  if (grid < 3 || grid > 1001)
    return "grid must be 3 to 1001 points across the disc, got " + std::to_string(grid);
  if (!std::isfinite(spin_max) || spin_max < 0.0)
    return describe("spin_max", "must be finite and not negative (0: the problem's limit)",
                    spin_max);
  if (threads < 0)
    return "threads must be 0 (one per core) or more, got " + std::to_string(threads);
  return {};
}

SpinMap spin_map(const problems::Problem& problem, double speed, double aim_deg,
                 const SpinMapOptions& options) {
  SpinMap map;
  map.speed = speed;
  map.aim_deg = aim_deg;
  map.grid = options.grid;
  map.spin_max = options.spin_max > 0.0 ? options.spin_max : problem.limits.spin_max;

  if (std::string why = options.validate(); !why.empty()) {
    map.message = why;
    return map;
  }
  if (!std::isfinite(speed) || !(speed > 0.0)) {
    map.message = describe("speed", "must be finite and above 0 (m/s)", speed);
    return map;
  }
  if (!std::isfinite(aim_deg)) {
    map.message = describe("aim_deg", "must be finite (deg)", aim_deg);
    return map;
  }
  if (!std::isfinite(map.spin_max) || !(map.spin_max > 0.0)) {
    map.message = describe("limits.spin", "must be finite and above 0", map.spin_max);
    return map;
  }

  // Only rest positions are kept: paths would cost memory and time for nothing.
  phys::SimulationOptions simulation = options.simulation;
  simulation.record_path = false;

  map.points = grid_points(options.grid, map.spin_max);
  const size_t total = map.points.size();
  const unsigned threads = worker_count(options.threads, total);

  // Each point is written by exactly one worker, into its own slot: the map is the
  // same for any number of threads. The calling thread works too and alone reports
  // progress, at most about a hundred times.
  std::atomic<size_t> next{0};
  std::atomic<size_t> done{0};
  size_t reported = 0;
  const auto report = [&] {
    const size_t finished = done.load();
    if (!options.progress || (finished - reported) * 100 < total) return;
    reported = finished;
    options.progress(static_cast<double>(finished) / static_cast<double>(total));
  };
  const auto drain = [&](bool reporting) {
    for (size_t i = next++; i < total; i = next++) {
      land(problem, speed, aim_deg, simulation, &map.points[i]);
      ++done;
      if (reporting) report();
    }
  };
  {
    std::vector<std::jthread> pool;
    pool.reserve(threads - 1);
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(drain, false);
    drain(true);
    // The last points may still be running on the workers.
    while (options.progress && done.load() < total) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      report();
    }
  }  // joins the workers
  if (options.progress) options.progress(1.0);

  map.landing = static_cast<int>(std::count_if(map.points.begin(), map.points.end(),
                                               [](const SpinMapPoint& p) { return p.lands; }));
  return map;
}

}  // namespace cueplan::planner
