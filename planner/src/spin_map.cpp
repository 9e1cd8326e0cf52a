// "What spin lands here?": one speed and aim, every spin on a square grid over the
// tip-offset disc, each simulated to rest on the problem's scene.
#include "cueplan/planner/spin_map.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "cueplan/parallel.hpp"
#include "robustness.hpp"
#include "search_space.hpp"
#include "task.hpp"

namespace cueplan::planner {
namespace {

namespace phys = cueplan::physics;

using phys::kSpinPerTipOffset;
using Clock = std::chrono::steady_clock;

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
// With a pot, the aim is solved for the spin (from `aim_deg`, the pot's ball sent
// `lateral_m` across its pocket).
void land(const detail::Task& task, double speed, double aim_deg, double lateral_m,
          const phys::SimulationOptions& simulation, SpinMapPoint* p) {
  const problems::Problem& problem = task.problem;
  phys::Shot shot{speed, aim_deg, p->topspin_k, p->sidespin_k};
  phys::ShotResult r;
  if (task.pot_aim) {
    detail::PotAim::Aimed aimed = task.pot_aim->aim(
        task, shot, simulation, detail::wrap_degrees(aim_deg - task.pot_aim->ghost_aim_deg()),
        lateral_m);
    shot = aimed.shot;
    r = std::move(aimed.result);
    using problems::Failure;
    const Failure f = problems::outcome_failure(problem, r);
    p->pots = aimed.found && f != Failure::first_contact && f != Failure::pot_missed &&
              f != Failure::wrong_pocket && f != Failure::other_ball_pocketed &&
              f != Failure::no_outcome;
  } else {
    r = task.simulate(shot, simulation);
  }
  p->aim_deg = shot.aim_deg;
  p->outcome = r.status;
  p->final_position = r.final_position;
  p->miss_distance = problems::miss_distance(problem, r);
  p->cushion_hits = r.cushion_hits;
  p->lands = problems::reaches_target(problem, r);
}

}  // namespace

phys::Validation SpinMapOptions::validate() const {
  using phys::invalid;
  if (grid < 3 || grid > 1001) return invalid({"grid"}, "must be 3 to 1001 points across the disc", grid);
  if (!std::isfinite(spin_max) || spin_max < 0.0)
    return invalid({"spin_max"}, "must be finite and not negative (0: the problem's limit)",
                   spin_max);
  if (threads < 0) return invalid({"threads"}, "must be 0 (one per core) or more", threads);
  if (success_samples < 0 || success_samples > 100000)
    return invalid({"success_samples"}, "must be 0 (not estimated) to 100000", success_samples);
  if (success_samples > 0) {
    if (phys::Validation e = noise.validate()) return e->under({"noise"});
  }
  return {};
}

SpinMap spin_map(const problems::Problem& problem, double speed, double aim_deg,
                 const SpinMapOptions& options) {
  SpinMap map;
  map.speed = speed;
  map.aim_deg = aim_deg;
  map.grid = options.grid;
  map.spin_max = options.spin_max > 0.0 ? options.spin_max : problem.limits.spin_max;

  const auto fail = [&map](phys::ValidationError error, std::string message) {
    map.message = std::move(message);
    map.error = std::move(error);
    return map;
  };
  if (phys::Validation e = options.validate()) return fail(*e, e->message());
  if (phys::Validation e = problems::validate(problem))
    return fail(*e, "problem: " + problems::file_message(*e));
  if (!std::isfinite(speed) || !(speed > 0.0)) {
    const phys::ValidationError e = phys::invalid({"speed"}, "must be finite and above 0 (m/s)", speed);
    return fail(e, e.message());
  }
  if (!std::isfinite(aim_deg)) {
    const phys::ValidationError e = phys::invalid({"aim_deg"}, "must be finite (deg)", aim_deg);
    return fail(e, e.message());
  }

  // Only rest positions are kept: paths would cost memory and time for nothing.
  phys::SimulationOptions simulation = options.simulation;
  simulation.record_path = false;

  map.points = grid_points(options.grid, map.spin_max);
  const size_t total = map.points.size();
  const unsigned threads = thread_count(options.threads, total);
  const detail::Task task(problem);

  // Each point is written by exactly one worker, into its own slot: the map is the
  // same for any number of threads. The calling thread works too and alone reports
  // progress, at most about a hundred times.
  size_t reported = 0;
  // A report at every whole per cent finished, and at the end.
  const auto report = [&](size_t finished) {
    if (!options.progress || ((finished - reported) * 100 < total && finished < total)) return;
    reported = finished;
    options.progress(static_cast<double>(finished) / static_cast<double>(total));
  };
  // A pot: the spins keep the pot where the given aim sends it with a centre-ball
  // stroke when that pots, else at the pocket's centre.
  double lateral = 0.0;
  if (task.pot_aim) {
    const phys::ShotResult centre = task.simulate({speed, aim_deg, 0.0, 0.0}, simulation);
    const std::optional<double> at = task.pot_aim->lateral_of(centre);
    const double reach = task.pot_aim->lateral_reach();
    if (at && problems::makes_pot(problem, centre)) lateral = std::clamp(*at, -reach, reach);
  }
  const bool estimate = options.success_samples > 0;
  if (!estimate) {
    parallel_for(
        total, threads,
        [&](size_t i, unsigned) { land(task, speed, aim_deg, lateral, simulation, &map.points[i]); },
        report);
  } else {
    // The estimates cost success_samples strokes a cell against one for the map: the
    // map's part of the progress is weighed so.
    const size_t first = std::min(options.success_first, total);
    const size_t count = std::min(options.success_count, total - first);
    const double map_share =
        1.0 / (1.0 + static_cast<double>(options.success_samples) * static_cast<double>(count) /
                         static_cast<double>(std::max<size_t>(total, 1)));
    int shown[2] = {-1, -1};  // the per cent last reported by each stage
    const auto weighed = [&](double share, double offset, size_t items, int* last) {
      return [&options, share, offset, items, last](size_t finished) {
        if (!options.progress) return;
        const int percent = static_cast<int>(100 * finished / std::max<size_t>(items, 1));
        if (percent == *last && finished < items) return;
        *last = percent;
        options.progress(offset + share * static_cast<double>(finished) /
                                      static_cast<double>(std::max<size_t>(items, 1)));
      };
    };
    parallel_for(
        total, threads,
        [&](size_t i, unsigned) { land(task, speed, aim_deg, lateral, simulation, &map.points[i]); },
        weighed(map_share, 0.0, total, &shown[0]));
    map.success_samples = options.success_samples;
    const std::vector<detail::NoiseDraw> draws =
        detail::noise_draws(options.success_samples, options.seed);
    const auto deadline = options.deadline;
    parallel_for(
        count, threads,
        [&](size_t j, unsigned) {
          SpinMapPoint& p = map.points[first + j];
          if (Clock::now() >= deadline) return;
          const phys::Shot shot{speed, p.aim_deg, p.topspin_k, p.sidespin_k};
          const detail::Sampled s =
              detail::sample_success(task, shot, draws, options.noise, simulation, deadline);
          // A cell the deadline cut short has no estimate.
          if (s.outcomes.size() == draws.size()) p.success = s.success.both.p;
        },
        weighed(1.0 - map_share, map_share, count, &shown[1]));
    for (const SpinMapPoint& p : map.points) map.success_cells += p.success.has_value();
    map.success_complete = map.success_cells == static_cast<int>(count);
  }

  map.landing = static_cast<int>(std::count_if(map.points.begin(), map.points.end(),
                                               [](const SpinMapPoint& p) { return p.lands; }));
  map.not_potting = static_cast<int>(std::count_if(
      map.points.begin(), map.points.end(), [](const SpinMapPoint& p) { return !p.pots; }));
  return map;
}

}  // namespace cueplan::planner
