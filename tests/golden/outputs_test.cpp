// A fixed set of rebound, simulate, solve and route outputs, every number written in
// hexadecimal floating point, compared with the dump committed beside this file.
//
// The comparison is exact on purpose: changes to how the code is organised (validation,
// helpers, stages) must leave every result bit-identical. A change that is meant to
// alter results (a new default, a new method) rewrites the dump in the same commit and
// says why: run the test with CUEPLAN_GOLDEN_WRITE=1 to write it.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "cueplan/physics/cushion_impact.hpp"
#include "cueplan/physics/shot.hpp"
#include "cueplan/planner/planner.hpp"
#include "cueplan/planner/route.hpp"
#include "cueplan/problems/problem.hpp"

namespace cueplan {
namespace {

std::string hex(double x) { return fmt::format("{:a}", x); }

void dump_impacts(std::string& out) {
  const physics::CushionParams params;
  int n = 0;
  for (physics::ImpactMethod method : {physics::ImpactMethod::exact, physics::ImpactMethod::paper}) {
    physics::ImpactOptions options;
    options.method = method;
    options.paper_steps = 400;
    for (double alpha : {1.0, 15.0, 45.0, 80.0, 90.0, 135.0}) {
      for (double kt : {-1.0, 0.0, 0.5, 1.0, 2.0}) {
        for (double ks : {-1.0, 0.0, 0.7}) {
          const double v = 0.3 + 0.7 * (n++ % 5);
          const physics::ImpactResult r = physics::resolve_impact(
              params, physics::incoming_state_k(v, alpha, kt, ks, params.radius), options);
          const physics::BallState& o = r.outgoing;
          out += fmt::format("rebound {} {} {} {} {}: {} {} {} {} {} {} {} {} {} {} {}\n",
                             physics::to_string(method), v, alpha, kt, ks,
                             physics::to_string(r.status), hex(o.velocity.x), hex(o.velocity.y),
                             hex(o.spin.x), hex(o.spin.y), hex(o.spin.z),
                             hex(r.impulse_compression), hex(r.impulse_total),
                             hex(r.work_compression), hex(r.work_total), r.transition_count);
        }
      }
    }
  }
  // Bad input comes back as a status with a message.
  physics::BallState away = physics::incoming_state(1.0, 45.0, 0.0, 0.0);
  away.velocity.y = -1.0;
  const physics::ImpactResult r = physics::resolve_impact(params, away);
  out += fmt::format("rebound away: {} {}\n", physics::to_string(r.status), r.message);
}

problems::Problem load(const std::string& name) {
  const problems::LoadResult r = problems::load_problem(std::string(CUEPLAN_PROBLEMS_DIR) + "/" + name);
  if (!r.ok()) ADD_FAILURE() << r.error;
  return r.ok() ? *r.problem : problems::Problem{};
}

void dump_shot(std::string& out, const std::string& label, const physics::ShotResult& r) {
  out += fmt::format("simulate {}: {} {} {} {} {} {} events {}\n", label,
                     physics::to_string(r.status), hex(r.final_position.x),
                     hex(r.final_position.y), hex(r.duration), r.cushion_hits,
                     hex(r.max_cushion_normal_speed), r.events.size());
  for (const physics::ShotEvent& e : r.events)
    out += fmt::format("  {} {} {} {} {} {} {} {} {} {}\n", physics::to_string(e.type),
                       hex(e.time), hex(e.position.x), hex(e.position.y), hex(e.velocity.x),
                       hex(e.velocity.y), hex(e.spin.z), e.cushion, e.index, hex(e.normal_speed));
}

void dump_shots(std::string& out) {
  const physics::Shot strokes[] = {{1.002, -60.36, 0.80, 0.0}, {1.227, 30.22, 1.0, 0.0},
                                   {1.943, 40.0, 1.0, 0.0},    {0.8, -30.0, 0.75, 1.0},
                                   {3.5, 170.0, -1.0, -0.6},   {0.5, 95.0, 0.0, 1.2},
                                   {4.4, 10.0, 1.2, 0.3}};
  for (const char* name : {"one_rail_position.yaml", "blocked_direct_route.yaml",
                           "pool_table.yaml", "carom_three_cushion.yaml", "near_pocket.yaml"}) {
    const problems::Problem p = load(name);
    int i = 0;
    for (const physics::Shot& s : strokes) {
      dump_shot(out, fmt::format("{} #{}", name, i++), physics::simulate(p.scene, p.cue_ball, s));
    }
    physics::SimulationOptions paper;
    paper.impact_method = physics::ImpactMethod::paper;
    dump_shot(out, fmt::format("{} paper", name), physics::simulate(p.scene, p.cue_ball, strokes[2], paper));
  }
}

void dump_planned(std::string& out, const std::string& label, const planner::PlannedShot& s) {
  out += fmt::format("  {}: {} {} {} {} -> {} {} {} miss {} cushions {} solves {} p {} [{} {}] of {} "
                     "family '{}' violations '{}'\n",
                     label, hex(s.shot.speed), hex(s.shot.aim_deg), hex(s.shot.topspin_k),
                     hex(s.shot.sidespin_k), physics::to_string(s.outcome), hex(s.final_position.x),
                     hex(s.final_position.y), hex(s.miss_distance), s.cushion_hits, s.solves,
                     hex(s.success_probability), hex(s.success.both.low), hex(s.success.both.high),
                     s.success.both.samples, s.family, s.violations);
}

// A plan the budget ends, not the clock: the same on every machine.
planner::PlannerOptions golden_plan_options() {
  planner::PlannerOptions options;
  options.max_evaluations = 800;
  options.max_time_s = 600.0;
  options.robustness_samples = 40;
  options.threads = 2;
  return options;
}

void dump_plans(std::string& out) {
  for (const char* name : {"one_rail_position.yaml", "near_pocket.yaml", "blocked_direct_route.yaml"}) {
    const problems::Problem p = load(name);
    const planner::PlannerOptions options = golden_plan_options();
    const planner::PlanResult r = planner::plan(p, options);
    out += fmt::format("solve {}: {} evaluations {} local {} converged {} message '{}'\n", name,
                       planner::to_string(r.status), r.evaluations, r.local_searches,
                       r.converged_searches, r.message.substr(0, r.message.find(" and succeeds")));
    dump_planned(out, "best", r.best);
    for (const planner::PlannedShot& a : r.alternatives) dump_planned(out, "alternative", a);
  }
}

// Pot plans: the stroke, its success condition by condition and the pot's report.
void dump_pot_plans(std::string& out) {
  for (const char* name : {"pots/cut_middle_pocket.yaml", "pots/long_pot.yaml"}) {
    const problems::Problem p = load(name);
    const planner::PlannerOptions options = golden_plan_options();
    const planner::PlanResult r = planner::plan(p, options);
    out += fmt::format("solve {}: {} evaluations {} local {} converged {}\n", name,
                       planner::to_string(r.status), r.evaluations, r.local_searches,
                       r.converged_searches);
    dump_planned(out, "best", r.best);
    for (const planner::PlannedShot* s : {&r.best}) {
      const planner::Success& u = s->success;
      if (u.pot)
        out += fmt::format("    pot p {} [{} {}] of {}; position p {} of {}\n", hex(u.pot->p),
                           hex(u.pot->low), hex(u.pot->high), u.pot->samples, hex(u.position.p),
                           u.position.samples);
      if (s->pot)
        out += fmt::format("    pot {} {} made {} cut {} {} throw {} ghost {} margin {} aim margin {}\n",
                           s->pot->ball, s->pot->pocket_name, s->pot->made, hex(s->pot->cut_deg),
                           s->pot->thickness, hex(s->pot->throw_deg), hex(s->pot->ghost_aim_deg),
                           hex(s->pot->margin_m), hex(s->pot->aim_margin_deg));
    }
    for (const planner::PlannedShot& a : r.alternatives) dump_planned(out, "alternative", a);
  }
}

void dump_routes(std::string& out) {
  planner::quiet_ompl_messages();
  const problems::Problem p = load("routes/two_stroke_blocked.yaml");
  planner::RouteOptions options;
  options.max_strokes = 2;
  options.max_time_s = 600.0;
  options.max_propagations = 60;
  options.steer_evaluations = 300;
  options.robustness_samples = 20;
  const planner::RouteResult r = planner::plan_route(p, options);
  out += fmt::format("route: {} strokes {} propagations {} steerings {} evaluations {}\n",
                     planner::to_string(r.status), r.strokes.size(), r.propagations, r.steerings,
                     r.evaluations);
  for (const planner::RouteStroke& s : r.strokes) dump_planned(out, "stroke", s.planned);
}

std::string dump() {
  std::string out;
  dump_impacts(out);
  dump_shots(out);
  dump_plans(out);
  dump_routes(out);
  dump_pot_plans(out);
  return out;
}

TEST(GoldenOutputs, EveryResultMatchesTheCommittedDump) {
  const std::string path = std::string(CUEPLAN_GOLDEN_DIR) + "/outputs.txt";
  const std::string now = dump();
  if (const char* write = std::getenv("CUEPLAN_GOLDEN_WRITE"); write && std::string(write) == "1") {
    std::ofstream(path, std::ios::binary) << now;
    GTEST_SKIP() << "wrote " << path;
  }
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << "no dump at " << path << " (write one with CUEPLAN_GOLDEN_WRITE=1)";
  std::stringstream committed;
  committed << in.rdbuf();
  // Line by line, so a difference is shown where it is.
  std::istringstream a(committed.str()), b(now);
  std::string la, lb;
  int line = 0;
  while (true) {
    const bool more_a = static_cast<bool>(std::getline(a, la));
    const bool more_b = static_cast<bool>(std::getline(b, lb));
    ++line;
    if (!more_a && !more_b) break;
    ASSERT_EQ(la, lb) << "first difference at line " << line << " of " << path;
  }
}

}  // namespace
}  // namespace cueplan
