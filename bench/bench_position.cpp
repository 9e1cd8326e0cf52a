// Position play (planner/position.hpp): the cost of a position field and of a next-ball
// plan, and how good the plans are, on generated snooker layouts.
//
//   build/bench/bench_position [--layouts N (30)] [--seed S (1)] [--pockets jawed|circles]
//
// Layouts: planner::known_pot_problems(N, S) (a cue ball, a red it can pot directly into
// a pocket) made position play: the target dropped, a black added at a random place
// (clear of the cushions, pockets and balls) and `next` the black into the pocket whose
// zone is largest. Each is planned as `cueplan solve` plans it (the impact table, exact
// verification, one thread). Measured per layout:
//   field      the PositionField build (ms);
//   plan       the whole plan, field included (wall and CPU ms);
//   pots       the best stroke re-simulated exactly pots the red;
//   next >= 0.6  the black solved (plan()) from where the cue ball stops has P(pot) >= 0.6;
//   agrees     that P(pot) lies within the reported success.next interval;
//   P(both)    the chosen stroke's P(pot and next) on 1000 fresh noisy strokes
//              (estimate_success), its mean over the layouts;
//   better     the landing's field value is above 80 % of the landings of the strokes that
//              pot the red (speeds 0.5-4.5 m/s, topspins -1.2..1.2 and sides -1..1 on a
//              grid within the spin limit, the aim solved for each as the planner solves
//              it): the positions the same pot reaches; also counted with ties (a landing
//              at least as good as 80 % of them, within 0.005: several reach a sure pot).
//
// --pockets jawed plays the same layouts on the snooker template's jawed pockets (a
// problem file's default table; the red was potted into a capture circle when the
// layout was made, so some reds may no longer drop); the default, circles, keeps the
// generated capture circles.
//
// Options for looking into the misses (the measure stays the same):
//   --scan            per layout, of the grid's potting strokes above: the best field value
//                     any of them leaves (an upper bound of what direct position play can
//                     reach), and the best P(both) (estimate_success, 100 strokes) of the
//                     12 best;
//   --verbose         the best stroke and the alternatives, each with its landing's field
//                     value and its success estimates;
//   --only N          plan and report only the N-th plannable layout (the others are
//                     still generated, so the layouts stay the same);
//   --evaluations N, --starts K, --robust N
//                     the planner's max_evaluations, local_starts, and its robust polish
//                     with robust_max_evaluations N.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "cueplan/physics/impact_table.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/position.hpp"
#include "cueplan/problems/problem.hpp"
#include "plan_stats.hpp"
#include "cueplan/api/table_cache.hpp"
#include "pot_aim.hpp"
#include "task.hpp"

namespace {

using namespace cueplan;
using bench::percentile;
using planner::describe_stroke;
using bench::thread_cpu_s;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) {
  return 1e3 * std::chrono::duration<double>(Clock::now() - t).count();
}

// A black at a random clear place, into the pocket whose zone is largest; false when
// no place was found.
bool make_position_play(problems::Problem* p, std::mt19937_64& rng, const planner::NoiseModel& noise) {
  const physics::Scene& s = p->scene;
  const double R = s.radius();
  std::uniform_real_distribution<double> x(0.15, s.length - 0.15), y(0.15, s.width - 0.15);
  for (int tries = 0; tries < 200; ++tries) {
    const physics::Vec2 black{x(rng), y(rng)};
    bool clear = std::hypot(black.x - p->cue_ball.x, black.y - p->cue_ball.y) > 2 * R + 0.1;
    for (const physics::ObjectBall& b : s.balls)
      clear = clear && std::hypot(black.x - b.position.x, black.y - b.position.y) > 2 * R + 0.1;
    for (const physics::Pocket& k : s.pockets)
      clear = clear && std::hypot(black.x - k.centre.x, black.y - k.centre.y) > 0.2;
    if (!clear) continue;
    problems::Problem q = *p;
    q.has_target = false;
    q.scene.balls.push_back({"black", black});
    double best = -1.0;
    int pocket = -1;
    for (int k = 0; k < static_cast<int>(s.pockets.size()); ++k) {
      q.next = {{"black", k}};
      if (problems::validate(q)) continue;
      // The pocket whose zone is largest: the easiest way to play the black.
      const planner::PositionField f = planner::PositionField::for_problem(q, noise);
      if (f.best_value() >= 0.5 && f.zone_area_m2() > best) best = f.zone_area_m2(), pocket = k;
    }
    if (pocket < 0) continue;
    q.next = {{"black", pocket}};
    q.name = p->name + " then black";
    *p = q;
    return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  int layouts = 30;
  uint64_t seed = 1;
  bool scan = false, verbose = false, jawed = false;
  int evaluations = 0, starts = 0, robust = 0, only = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--layouts") layouts = std::atoi(next().c_str());
    else if (a == "--seed") seed = std::strtoull(next().c_str(), nullptr, 10);
    else if (a == "--scan") scan = true;
    else if (a == "--verbose") verbose = true;
    else if (a == "--pockets") {
      const std::string kind = next();
      if (kind != "jawed" && kind != "circles") {
        fmt::print(stderr, "bench_position: --pockets takes jawed or circles, not '{}'\n", kind);
        return 2;
      }
      jawed = kind == "jawed";
    }
    else if (a == "--only") only = std::atoi(next().c_str());
    else if (a == "--evaluations") evaluations = std::atoi(next().c_str());
    else if (a == "--starts") starts = std::atoi(next().c_str());
    else if (a == "--robust") robust = std::atoi(next().c_str());
    else {
      fmt::print(stderr, "bench_position: unknown argument {}\n", a);
      return 2;
    }
  }
  const physics::Scene snooker = physics::snooker_scene();
  std::string note;
  const physics::ImpactTable table = cli::load_or_build_table(
      snooker.ball_and_cushion, physics::ImpactTableOptions{}, cli::default_table_cache_dir(), &note);
  physics::SimulationOptions sim;
  sim.impact_method = physics::ImpactMethod::table;
  sim.table = &table;
  sim.impact_accuracy = 5e-6;  // as `cueplan solve` searches with the table
  physics::SimulationOptions exact;
  exact.record_path = false;

  planner::PlannerOptions options;
  options.simulation = sim;
  options.simulation.record_path = false;
  options.threads = 1;
  if (evaluations > 0) options.max_evaluations = evaluations;
  if (starts > 0) options.local_starts = starts;
  if (robust > 0) options.robust = true, options.robust_max_evaluations = robust;
  std::mt19937_64 rng(seed);

  std::vector<double> field_ms, plan_ms, plan_cpu_ms, next_p, reported, fresh_both;
  int count = 0, solved = 0, pots = 0, next_ok = 0, agrees = 0, better = 0, as_good = 0, in_zone = 0;
  int scan_reach = 0;  // --scan: layouts where some potting stroke lands where the field is >= 0.6
  for (planner::KnownShotProblem& k : planner::known_pot_problems(layouts, seed, sim)) {
    problems::Problem p = k.problem;
    if (jawed) {
      // The snooker template's jawed pockets (a problem file's default table).
      const physics::PocketPreset preset = *physics::pocket_preset("snooker");
      p.scene.pockets = physics::jawed_pockets(p.scene.length, p.scene.width, preset.corner, preset.middle);
      if (problems::validate(p)) continue;
    }
    if (!make_position_play(&p, rng, options.noise)) continue;
    ++count;
    if (only > 0 && count != only) continue;
    // Warm, then timed: the field alone.
    (void)planner::PositionField::for_problem(p, options.noise);
    const Clock::time_point f0 = Clock::now();
    const planner::PositionField field = planner::PositionField::for_problem(p, options.noise);
    field_ms.push_back(ms_since(f0));

    const double cpu0 = thread_cpu_s();
    const planner::PlanResult r = planner::plan(p, options);
    plan_cpu_ms.push_back(1e3 * (thread_cpu_s() - cpu0));
    plan_ms.push_back(1e3 * r.time_s);
    if (r.status != planner::PlanStatus::solved) {
      fmt::print(stderr, "{}: {}\n", p.name, r.message);
      continue;
    }
    ++solved;
    const planner::PlannedShot& b = r.best;
    if (verbose) {
      std::vector<const planner::PlannedShot*> shown{&b};
      for (const planner::PlannedShot& a : r.alternatives) shown.push_back(&a);
      for (const planner::PlannedShot* a : shown)
        fmt::print(stderr, "  {} landing value {:.2f}, pot {:.2f}, next {:.2f}, both {:.2f} ({} strokes): {}\n",
                   a == &b ? "best" : "alt ", field.value(a->final_position),
                   a->success.pot ? a->success.pot->p : 0.0, a->success.next ? a->success.next->p : 0.0,
                   a->success.both.p, a->success.both.samples, describe_stroke(a->shot));
    }
    pots += problems::makes_pot(p, physics::simulate(p.scene, p.cue_ball, b.shot, exact));
    in_zone += b.next && b.next->in_zone;
    // The chosen stroke's P(both) on fresh noise draws (not the plan's own).
    fresh_both.push_back(
        planner::estimate_success(p, b.shot, options.noise, 1000, 0x66726573ULL, options.simulation).both.p);

    // The black from where the cue ball stops, the red gone.
    problems::Problem n = p;
    n.scene.balls.erase(std::remove_if(n.scene.balls.begin(), n.scene.balls.end(),
                                       [&](const physics::ObjectBall& o) { return o.name == p.pot->ball; }),
                        n.scene.balls.end());
    n.cue_ball = b.final_position;
    n.pot = problems::Pot{"black", p.next.front().pocket};
    n.first_contact.reset();
    n.next.clear();
    double p_next = 0.0;
    if (!problems::validate(n)) {
      const planner::PlanResult m = planner::plan(n, options);
      if (m.status == planner::PlanStatus::solved && m.best.success.pot) p_next = m.best.success.pot->p;
      const planner::PositionField check(n.scene, {{"black", n.pot->pocket}}, options.noise);
      fmt::print(stderr, "  next problem: field at its cue ball {:.2f} (cut {:.1f}); planner {} {:.2f} {}; pockets jawed {}\n",
                 check.next_shot(n.cue_ball).p, check.next_shot(n.cue_ball).cut_deg,
                 planner::to_string(m.status), p_next, describe_stroke(m.best.shot),
                 n.scene.pockets.front().jaws.has_value());
    }
    next_p.push_back(p_next);
    next_ok += p_next >= 0.6;
    if (b.success.next) {
      reported.push_back(b.success.next->p);
      agrees += p_next >= b.success.next->low && p_next <= b.success.next->high;
    }

    // The positions the same pot reaches: strokes on a grid of speed, topspin and side,
    // the aim solved for each as the planner solves it, those that pot the red.
    const planner::detail::Task task(p);
    struct Cand { double nominal; physics::Shot shot; };
    std::vector<Cand> cands;
    for (double v = 0.5; v <= 4.5 + 1e-9; v += 0.25)
      for (double kt = -1.2; kt <= 1.2 + 1e-9; kt += 0.2)
        for (double ks = -1.0; ks <= 1.0 + 1e-9; ks += 0.5) {
          if (std::hypot(kt, ks) > p.limits.spin_max) continue;
          physics::Shot s = b.shot;
          s.speed = v; s.topspin_k = kt; s.sidespin_k = ks;
          const auto aimed = task.pot_aim->aim(task, s, options.simulation);
          if (!aimed.found || !problems::check_outcome(p, aimed.result).pot_made()) continue;
          cands.push_back({field.value(aimed.result.final_position), aimed.shot});
        }
    const double landing_value = field.value(b.final_position);
    int below = 0, not_above = 0;
    double best_reached = 0.0;
    for (const Cand& c : cands) {
      below += c.nominal < landing_value;
      not_above += c.nominal <= landing_value + 0.005;
      best_reached = std::max(best_reached, c.nominal);
    }
    const int reached = static_cast<int>(cands.size());
    better += reached > 0 && below >= 0.8 * reached;
    as_good += reached > 0 && not_above >= 0.8 * reached;
    if (scan) {
      std::sort(cands.begin(), cands.end(), [](const Cand& x, const Cand& y) { return x.nominal > y.nominal; });
      double best_obj = 0.0, best_nom = cands.empty() ? 0.0 : cands.front().nominal;
      physics::Shot best_shot;
      for (size_t c = 0; c < std::min<size_t>(cands.size(), 12); ++c) {
        const planner::Success su = planner::estimate_success(p, cands[c].shot, options.noise, 100, 7, options.simulation);
        const double obj = su.both.p;
        if (obj > best_obj) best_obj = obj, best_shot = cands[c].shot;
      }
      const planner::Success mine = planner::estimate_success(p, b.shot, options.noise, 100, 7, options.simulation);
      scan_reach += best_nom >= 0.6;
      fmt::print(stderr, "  SCAN {}: potting strokes {}, best nominal value {:.2f}, best both {:.2f} ({}); planner's both {:.2f} nominal {:.2f}\n",
                 p.name, cands.size(), best_nom, best_obj, describe_stroke(best_shot), mine.both.p, landing_value);
    }
    fmt::print(stderr, "{}: field {:.1f} ms, plan {:.0f} ms; next reported {:.2f}, solved from the "
                       "landing {:.2f}; landing above {}/{} reached positions (best reached {:.2f}, field best {:.2f}, "
                       "landing {:.2f}: {}; {}; pocket {})\n",
               p.name, field_ms.back(), plan_ms.back(), b.success.next ? b.success.next->p : 0.0,
               p_next, below, reached, best_reached, field.best_value(), landing_value,
               b.next ? b.next->words : "", describe_stroke(b.shot),
               problems::pocket_name(p.scene, p.next.front().pocket));
  }
  fmt::print("impact table: {}\n", note);
  fmt::print("layouts {} (seed {}), solved {}, the red potted on re-simulation {}\n", count, seed,
             solved, pots);
  fmt::print("| measure | median | p95 |\n|---|---|---|\n");
  fmt::print("| field build (ms) | {:.1f} | {:.1f} |\n", percentile(field_ms, 0.5), percentile(field_ms, 0.95));
  fmt::print("| next-ball plan, wall (ms) | {:.0f} | {:.0f} |\n", percentile(plan_ms, 0.5), percentile(plan_ms, 0.95));
  fmt::print("| next-ball plan, CPU (ms) | {:.0f} | {:.0f} |\n", percentile(plan_cpu_ms, 0.5),
             percentile(plan_cpu_ms, 0.95));
  const auto pct = [&](int k) { return 100.0 * k / std::max(1, solved); };
  fmt::print("next pot from the landing solved with P(pot) >= 0.6: {}/{} ({:.0f} %)\n", next_ok, solved, pct(next_ok));
  fmt::print("within the reported success.next interval: {}/{} ({:.0f} %)\n", agrees, solved, pct(agrees));
  fmt::print("landing above 80 % of the positions the same pot reaches: {}/{} ({:.0f} %)\n", better,
             solved, pct(better));
  double mean_both = 0.0;
  for (double q : fresh_both) mean_both += q / std::max<size_t>(1, fresh_both.size());
  fmt::print("the chosen strokes' P(both) on 1000 fresh noisy strokes: mean {:.3f}\n", mean_both);
  fmt::print("landing at least as good as 80 % of them (within 0.005): {}/{} ({:.0f} %)\n", as_good,
             solved, pct(as_good));
  fmt::print("landing inside the zone: {}/{} ({:.0f} %)\n", in_zone, solved, pct(in_zone));
  if (scan)
    fmt::print("scan: some potting stroke lands where the field is >= 0.6: {}/{} ({:.0f} %)\n", scan_reach,
               solved, pct(scan_reach));
  return 0;
}
